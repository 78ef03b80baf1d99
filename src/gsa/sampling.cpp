#include "gsa/sampling.hpp"

#include <cmath>
#include <string>

#include "common/error.hpp"
#include "sweep/design.hpp"

namespace phasmid::gsa {
namespace {

constexpr int kBits = 52;  // sweep::sobol_points returns multiples of 2^-52
const double kScale = std::ldexp(1.0, kBits);

// Random non-singular lower-triangular GF(2) matrix, one mask per output digit: digit i
// (most significant first, bit kBits-1-i) becomes itself XOR a random subset of the more
// significant digits. Lower-triangular in the digit order keeps the (t,m,s)-net property.
std::vector<std::uint64_t> random_ltm(sweep::SplitMix64& rng) {
  std::vector<std::uint64_t> rows(kBits);
  const std::uint64_t all = (std::uint64_t(1) << kBits) - 1;
  for (int b = 0; b < kBits; ++b) {
    const std::uint64_t above = all & ~((std::uint64_t(2) << b) - 1);  // bits b+1 .. kBits-1
    rows[b] = (std::uint64_t(1) << b) | (rng.next() & above);
  }
  return rows;
}

std::uint64_t apply_ltm(const std::vector<std::uint64_t>& rows, std::uint64_t x) {
  std::uint64_t out = 0;
  for (int b = 0; b < kBits; ++b) out |= static_cast<std::uint64_t>(__builtin_parityll(rows[b] & x)) << b;
  return out;
}

void check_dim(std::size_t dim, const char* what) {
  if (dim == 0) throw Error(std::string(what) + ": needs at least one parameter");
}

}  // namespace

std::vector<double> scrambled_sobol_points(std::size_t n, std::size_t dim, bool scramble, std::size_t skip,
                                           std::uint64_t seed) {
  std::vector<double> all = sweep::sobol_points(n + skip, dim);
  std::vector<double> out(all.begin() + static_cast<std::ptrdiff_t>(skip * dim), all.end());
  if (!scramble) return out;
  sweep::SplitMix64 rng{seed};
  const std::uint64_t mask = (std::uint64_t(1) << kBits) - 1;
  for (std::size_t d = 0; d < dim; ++d) {
    const std::vector<std::uint64_t> ltm = random_ltm(rng);
    const std::uint64_t shift = rng.next() & mask;
    for (std::size_t i = 0; i < n; ++i) {
      double& u = out[i * dim + d];
      const auto x = static_cast<std::uint64_t>(u * kScale);  // exact: u is a multiple of 2^-52
      u = static_cast<double>(apply_ltm(ltm, x) ^ shift) / kScale;
    }
  }
  return out;
}

SaltelliDesign saltelli_sample(std::size_t dim, const SaltelliOptions& o) {
  check_dim(dim, "saltelli design");
  if (2 * dim > sweep::kSobolMaxDim)
    throw Error("saltelli design: at most " + std::to_string(sweep::kSobolMaxDim / 2) + " parameters, got " +
                std::to_string(dim));
  if (o.n_base < 2) throw Error("saltelli design: the base sample size N must be at least 2");
  SaltelliDesign s;
  s.n_base = o.n_base;
  s.dim = dim;
  s.second_order = o.second_order;
  const std::vector<double> base = scrambled_sobol_points(o.n_base, 2 * dim, o.scramble, o.skip, o.seed);
  const std::size_t blk = s.block();
  s.unit.resize(s.rows() * dim);
  for (std::size_t i = 0; i < o.n_base; ++i) {
    const double* a = &base[i * 2 * dim];
    const double* b = a + dim;
    auto row = [&](std::size_t k) { return &s.unit[(i * blk + k) * dim]; };
    for (std::size_t d = 0; d < dim; ++d) {
      row(0)[d] = a[d];
      row(blk - 1)[d] = b[d];
      for (std::size_t j = 0; j < dim; ++j) {
        row(1 + j)[d] = d == j ? b[d] : a[d];                              // AB^(j)
        if (s.second_order) row(1 + dim + j)[d] = d == j ? a[d] : b[d];  // BA^(j)
      }
    }
  }
  return s;
}

namespace {

// One trajectory in grid-level units (0..p-1): a random start with each coordinate at its
// lower level l (l + p/2 <= p-1) or at l + p/2, then each coordinate, in random order, moves
// by p/2 levels (= Delta) towards the other end.
std::vector<int> morris_trajectory(std::size_t dim, int p, sweep::SplitMix64& rng) {
  const int half = p / 2;
  std::vector<int> x(dim), dir(dim);
  std::vector<std::size_t> order(dim);
  for (std::size_t d = 0; d < dim; ++d) {
    const int lower = static_cast<int>(rng.below(static_cast<std::uint64_t>(half)));
    dir[d] = rng.below(2) ? 1 : -1;
    x[d] = dir[d] > 0 ? lower : lower + half;
    order[d] = d;
  }
  for (std::size_t i = dim; i > 1; --i) std::swap(order[i - 1], order[rng.below(i)]);
  std::vector<int> t(x);
  for (std::size_t k = 0; k < dim; ++k) {
    x[order[k]] += dir[order[k]] * half;
    t.insert(t.end(), x.begin(), x.end());
  }
  return t;
}

// Campolongo et al. (2007) spread of two trajectories: the sum over all pairs of their points
// of the Euclidean distance (in level units; a constant factor does not change the choice).
double trajectory_distance(const std::vector<int>& a, const std::vector<int>& b, std::size_t dim) {
  double sum = 0;
  for (std::size_t i = 0; i <= dim; ++i)
    for (std::size_t j = 0; j <= dim; ++j) {
      double s2 = 0;
      for (std::size_t d = 0; d < dim; ++d) {
        const double diff = a[i * dim + d] - b[j * dim + d];
        s2 += diff * diff;
      }
      sum += std::sqrt(s2);
    }
  return sum;
}

// Greedy version of Campolongo's selection (the exact one enumerates all r-subsets): start
// with the most distant pair, then add the trajectory that most increases sum of d^2 over the
// chosen pairs, until r are chosen.
std::vector<std::size_t> select_by_spread(const std::vector<std::vector<int>>& pool, std::size_t r, std::size_t dim) {
  const std::size_t m = pool.size();
  std::vector<double> d2(m * m, 0.0);
  std::size_t best_a = 0, best_b = 1;
  for (std::size_t a = 0; a < m; ++a)
    for (std::size_t b = a + 1; b < m; ++b) {
      const double d = trajectory_distance(pool[a], pool[b], dim);
      d2[a * m + b] = d2[b * m + a] = d * d;
      if (d2[a * m + b] > d2[best_a * m + best_b]) best_a = a, best_b = b;
    }
  std::vector<std::size_t> chosen{best_a, best_b};
  std::vector<bool> used(m, false);
  used[best_a] = used[best_b] = true;
  while (chosen.size() < r) {
    std::size_t best = m;
    double best_gain = -1;
    for (std::size_t c = 0; c < m; ++c) {
      if (used[c]) continue;
      double gain = 0;
      for (std::size_t s : chosen) gain += d2[c * m + s];
      if (gain > best_gain) best_gain = gain, best = c;
    }
    chosen.push_back(best);
    used[best] = true;
  }
  return chosen;
}

}  // namespace

MorrisDesign morris_sample(std::size_t dim, const MorrisOptions& o) {
  check_dim(dim, "morris design");
  if (o.levels < 2 || o.levels % 2 != 0)
    throw Error("morris design: levels must be even and >= 2, got " + std::to_string(o.levels));
  if (o.trajectories < 2) throw Error("morris design: needs at least 2 trajectories");
  if (o.pool != 0 && o.pool <= o.trajectories)
    throw Error("morris design: the selection pool (" + std::to_string(o.pool) +
                ") must be larger than the number of trajectories (" + std::to_string(o.trajectories) + ")");
  sweep::SplitMix64 rng{o.seed};
  std::vector<std::vector<int>> pool(o.pool ? o.pool : o.trajectories);
  for (auto& t : pool) t = morris_trajectory(dim, o.levels, rng);
  std::vector<std::size_t> pick;
  if (o.pool) pick = select_by_spread(pool, o.trajectories, dim);
  else
    for (std::size_t k = 0; k < o.trajectories; ++k) pick.push_back(k);
  MorrisDesign m;
  m.dim = dim;
  m.trajectories = o.trajectories;
  m.levels = o.levels;
  m.delta = o.levels / (2.0 * (o.levels - 1));
  for (std::size_t k : pick)
    for (int level : pool[k]) m.unit.push_back(static_cast<double>(level) / (o.levels - 1));
  return m;
}

std::vector<double> scale_to_parameters(const std::vector<double>& unit, const std::vector<Parameter>& parameters) {
  const std::size_t dim = parameters.size();
  if (dim == 0 || unit.size() % dim != 0)
    throw Error("gsa: design with " + std::to_string(unit.size()) + " values does not fit " + std::to_string(dim) +
                " parameters");
  std::vector<double> out(unit.size());
  for (std::size_t i = 0; i < unit.size(); ++i) out[i] = sweep::map_unit(parameters[i % dim], unit[i]);
  return out;
}

}  // namespace phasmid::gsa
