#include "sweep/design.hpp"

#include <string>

#include "common/error.hpp"

namespace phasmid::sweep {
namespace {

// Joe & Kuo (2008), file new-joe-kuo-6.21201, dimensions 2..32: "s a m_1 ... m_s" per row.
// (Dimension 1 is the van der Corput sequence and needs none.)
const char* const kJoeKuo[kSobolMaxDim - 1] = {
    "1 0 1",          "2 1 1 3",         "3 1 1 3 1",         "3 2 1 1 1",          "4 1 1 1 3 3",
    "4 4 1 3 5 13",   "5 2 1 1 5 5 17",  "5 4 1 1 5 5 5",     "5 7 1 1 7 11 19",    "5 11 1 1 5 1 1",
    "5 13 1 1 1 3 11", "5 14 1 3 5 5 31", "6 1 1 3 3 9 7 49", "6 13 1 1 1 15 21 21", "6 16 1 3 1 13 27 49",
    "6 19 1 1 1 15 7 5", "6 22 1 3 1 15 13 25", "6 25 1 1 5 5 19 61", "7 1 1 3 7 11 23 15 103",
    "7 4 1 3 7 13 13 15 69", "7 7 1 1 3 13 7 35 63", "7 8 1 3 5 9 1 25 53", "7 14 1 3 1 13 9 35 107",
    "7 19 1 3 1 5 27 61 31", "7 21 1 1 5 11 19 41 61", "7 28 1 3 5 3 3 13 69", "7 31 1 1 7 13 1 19 1",
    "7 32 1 3 7 5 13 19 59", "7 37 1 1 3 9 25 29 41", "7 41 1 3 5 13 23 1 55", "7 42 1 3 7 3 13 59 17",
};

constexpr int kBits = 52;  // points are multiples of 2^-52: exact in a double

std::vector<unsigned> parse_row(const char* row) {
  std::vector<unsigned> v;
  std::string s(row);
  size_t pos = 0;
  while (pos < s.size()) {
    size_t end = s.find(' ', pos);
    if (end == std::string::npos) end = s.size();
    v.push_back(static_cast<unsigned>(std::stoul(s.substr(pos, end - pos))));
    pos = end + 1;
  }
  return v;
}

// Direction numbers v[k] (k = 0..kBits-1) of one dimension, scaled by 2^kBits.
std::vector<std::uint64_t> directions(std::size_t d) {
  std::vector<std::uint64_t> v(kBits);
  if (d == 0) {
    for (int k = 0; k < kBits; ++k) v[k] = std::uint64_t(1) << (kBits - 1 - k);
    return v;
  }
  std::vector<unsigned> row = parse_row(kJoeKuo[d - 1]);
  const unsigned s = row[0], a = row[1];
  for (unsigned k = 0; k < s && k < static_cast<unsigned>(kBits); ++k)
    v[k] = static_cast<std::uint64_t>(row[2 + k]) << (kBits - 1 - k);
  for (unsigned k = s; k < static_cast<unsigned>(kBits); ++k) {
    v[k] = v[k - s] ^ (v[k - s] >> s);
    for (unsigned j = 1; j < s; ++j)
      if ((a >> (s - 1 - j)) & 1u) v[k] ^= v[k - j];
  }
  return v;
}

}  // namespace

std::vector<double> sobol_points(std::size_t n, std::size_t dim) {
  if (dim == 0 || dim > kSobolMaxDim)
    throw Error("sobol design supports 1 to " + std::to_string(kSobolMaxDim) + " parameters, got " +
                std::to_string(dim));
  if (n > (std::size_t(1) << 31)) throw Error("sobol design: too many points");
  std::vector<std::vector<std::uint64_t>> v(dim);
  for (std::size_t d = 0; d < dim; ++d) v[d] = directions(d);
  std::vector<double> out(n * dim);
  std::vector<std::uint64_t> x(dim, 0);
  const double scale = 1.0 / static_cast<double>(std::uint64_t(1) << kBits);
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0) {
      // Gray-code update: flip the direction number of the lowest zero bit of i-1.
      std::size_t c = 0, m = i - 1;
      while (m & 1) {
        m >>= 1;
        ++c;
      }
      for (std::size_t d = 0; d < dim; ++d) x[d] ^= v[d][c];
    }
    for (std::size_t d = 0; d < dim; ++d) out[i * dim + d] = static_cast<double>(x[d]) * scale;
  }
  return out;
}

std::uint64_t SplitMix64::next() {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

double SplitMix64::uniform() { return static_cast<double>(next() >> 11) * (1.0 / 9007199254740992.0); }

std::uint64_t SplitMix64::below(std::uint64_t n) {
  const std::uint64_t limit = UINT64_MAX - UINT64_MAX % n;
  std::uint64_t r;
  do r = next();
  while (r >= limit);
  return r % n;
}

std::vector<double> lhs_points(std::size_t n, std::size_t dim, std::uint64_t seed) {
  std::vector<double> out(n * dim);
  SplitMix64 rng{seed};
  std::vector<std::size_t> perm(n);
  for (std::size_t d = 0; d < dim; ++d) {
    for (std::size_t i = 0; i < n; ++i) perm[i] = i;
    for (std::size_t i = n; i > 1; --i) std::swap(perm[i - 1], perm[rng.below(i)]);  // Fisher-Yates
    for (std::size_t i = 0; i < n; ++i) out[i * dim + d] = (static_cast<double>(perm[i]) + rng.uniform()) / n;
  }
  return out;
}

}  // namespace phasmid::sweep
