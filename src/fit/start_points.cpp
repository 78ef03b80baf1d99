#include "fit/start_points.hpp"

#include <algorithm>
#include <numeric>
#include <random>

#include "common/error.hpp"

namespace phasmid::fit {

Sampling parse_sampling(const std::string& s) {
  if (s == "lhs" || s == "latin_hypercube") return Sampling::LatinHypercube;
  if (s == "sobol") return Sampling::Sobol;
  throw Error("start sampling must be \"lhs\" or \"sobol\", got '" + s + "'");
}

std::vector<std::vector<double>> latin_hypercube(size_t n, size_t dim, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::vector<double>> pts(n, std::vector<double>(dim));
  std::vector<size_t> perm(n);
  for (size_t d = 0; d < dim; ++d) {
    std::iota(perm.begin(), perm.end(), 0);
    // Fisher-Yates with our own draws (std::shuffle's algorithm is implementation-defined).
    for (size_t i = n; i > 1; --i) {
      size_t j = static_cast<size_t>(u(rng) * i);
      std::swap(perm[i - 1], perm[std::min(j, i - 1)]);
    }
    for (size_t i = 0; i < n; ++i) pts[i][d] = (perm[i] + u(rng)) / static_cast<double>(n);
  }
  return pts;
}

namespace {
// Joe & Kuo (2008), new-joe-kuo-6.21201, dimensions 2..21: degree s, coefficients a, m_1..m_s.
struct Dir {
  unsigned s, a;
  unsigned m[8];
};
const Dir kDirs[] = {
    {1, 0, {1}},
    {2, 1, {1, 3}},
    {3, 1, {1, 3, 1}},
    {3, 2, {1, 1, 1}},
    {4, 1, {1, 1, 3, 3}},
    {4, 4, {1, 3, 5, 13}},
    {5, 2, {1, 1, 5, 5, 17}},
    {5, 4, {1, 1, 5, 5, 5}},
    {5, 7, {1, 1, 7, 11, 19}},
    {5, 11, {1, 1, 5, 1, 1}},
    {5, 13, {1, 1, 1, 3, 11}},
    {5, 14, {1, 3, 5, 5, 31}},
    {6, 1, {1, 3, 3, 9, 7, 49}},
    {6, 13, {1, 1, 1, 15, 21, 21}},
    {6, 16, {1, 3, 1, 13, 27, 49}},
    {6, 19, {1, 1, 1, 15, 7, 5}},
    {6, 22, {1, 3, 1, 15, 13, 25}},
    {6, 25, {1, 1, 5, 5, 19, 61}},
    {7, 1, {1, 3, 7, 11, 23, 15, 103}},
    {7, 4, {1, 3, 7, 13, 13, 15, 69}},
};
constexpr unsigned kBits = 52;
}  // namespace

std::vector<std::vector<double>> sobol(size_t n, size_t dim, std::uint64_t seed) {
  if (dim > kSobolMaxDim) throw Error("Sobol starts support up to " + std::to_string(kSobolMaxDim) + " parameters; use lhs");
  std::vector<std::vector<std::uint64_t>> V(dim, std::vector<std::uint64_t>(kBits + 1));
  for (unsigned i = 1; i <= kBits; ++i) V[0][i] = std::uint64_t(1) << (kBits - i);
  for (size_t d = 1; d < dim; ++d) {
    const Dir& D = kDirs[d - 1];
    for (unsigned i = 1; i <= kBits; ++i) {
      if (i <= D.s) {
        V[d][i] = std::uint64_t(D.m[i - 1]) << (kBits - i);
      } else {
        std::uint64_t v = V[d][i - D.s] ^ (V[d][i - D.s] >> D.s);
        for (unsigned k = 1; k < D.s; ++k) v ^= ((D.a >> (D.s - 1 - k)) & 1u) * V[d][i - k];
        V[d][i] = v;
      }
    }
  }
  std::vector<std::uint64_t> shift(dim, 0);
  if (seed) {
    std::mt19937_64 rng(seed);
    for (auto& s : shift) s = rng() >> (64 - kBits);
  }
  std::vector<std::vector<double>> pts;
  std::vector<std::uint64_t> X(dim, 0);
  const double scale = 1.0 / static_cast<double>(std::uint64_t(1) << kBits);
  for (std::uint64_t i = 1; i <= n; ++i) {
    // Gray-code update: flip the direction number of the lowest zero bit of i-1.
    unsigned c = 1;
    std::uint64_t v = i - 1;
    while (v & 1) {
      v >>= 1;
      ++c;
    }
    std::vector<double> p(dim);
    for (size_t d = 0; d < dim; ++d) {
      X[d] ^= V[d][c];
      p[d] = static_cast<double>(X[d] ^ shift[d]) * scale;
    }
    pts.push_back(p);
  }
  return pts;
}

std::vector<std::vector<double>> start_points(Sampling s, size_t n, const std::vector<double>& lo,
                                              const std::vector<double>& hi, std::uint64_t seed) {
  auto u = s == Sampling::Sobol ? sobol(n, lo.size(), seed) : latin_hypercube(n, lo.size(), seed);
  for (auto& p : u)
    for (size_t d = 0; d < p.size(); ++d) p[d] = lo[d] + p[d] * (hi[d] - lo[d]);
  return u;
}

}  // namespace phasmid::fit
