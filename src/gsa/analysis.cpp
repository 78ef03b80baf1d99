#include "gsa/analysis.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "common/error.hpp"
#include "sweep/design.hpp"

namespace phasmid::gsa {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Running mean and variance of bootstrap replicates, one slot per index (Welford).
// Running mean and variance of bootstrap replicates, per slot. A replicate that is not finite
// in a slot (a resample whose outputs are all equal has no variance to apportion, which happens
// for rare 0/1 outputs) is left out of that slot.
struct Spread {
  std::vector<double> mean, m2;
  std::vector<std::size_t> n;
  explicit Spread(std::size_t k) : mean(k, 0.0), m2(k, 0.0), n(k, 0) {}
  void add(const std::vector<double>& x) {
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (!std::isfinite(x[i])) continue;
      const double d = x[i] - mean[i];
      mean[i] += d / static_cast<double>(++n[i]);
      m2[i] += d * (x[i] - mean[i]);
    }
  }
  // z * sd (divisor n-1) per slot; NaN with fewer than two finite replicates.
  std::vector<double> half_width(double z) const {
    std::vector<double> out(mean.size(), kNaN);
    for (std::size_t i = 0; i < out.size(); ++i)
      if (n[i] >= 2) out[i] = z * std::sqrt(m2[i] / static_cast<double>(n[i] - 1));
    return out;
  }
};

void check_bootstrap(const BootstrapOptions& b) {
  if (!(b.confidence > 0 && b.confidence < 1))
    throw Error("gsa: confidence level must lie in (0, 1), got " + std::to_string(b.confidence));
}

// As many items as `items` holds, drawn from it with replacement.
std::vector<std::size_t> resample(const std::vector<std::size_t>& items, sweep::SplitMix64& rng) {
  std::vector<std::size_t> out(items.size());
  for (auto& o : out) o = items[rng.below(items.size())];
  return out;
}

struct SobolLayout {
  const std::vector<double>& y;
  std::size_t dim, block;
  bool second_order;
};

// Mean of the A and B outputs of the listed blocks.
double ab_mean(const SobolLayout& L, const std::vector<std::size_t>& rows) {
  double mean = 0;
  for (std::size_t r : rows) mean += L.y[r * L.block] + L.y[r * L.block + L.block - 1];
  return mean / (2.0 * rows.size());
}

// V: variance of the A and B outputs of the listed blocks together (divisor 2n), about their mean.
double ab_variance(const SobolLayout& L, const std::vector<std::size_t>& rows, double mean) {
  double var = 0;
  for (std::size_t r : rows) {
    const double a = L.y[r * L.block] - mean, b = L.y[r * L.block + L.block - 1] - mean;
    var += a * a + b * b;
  }
  return var / (2.0 * rows.size());
}

// S1 (first dim slots), ST (next dim) and, with second order, S2 (dim x dim, upper triangle)
// from the base-row blocks listed in `rows` (repetitions allowed). The outputs are centred by
// their A-and-B mean first: the S1 and S2 estimators are products of outputs, not invariant to
// a shift of f, and an output whose mean is large against its spread (a period of 500 ms that
// varies by a few ms) would otherwise add mean^2/V to their variance. The shift changes
// neither estimator's expectation (E[f(AB) - f(A)] = 0) nor ST (differences only).
std::vector<double> sobol_estimate(const SobolLayout& L, const std::vector<std::size_t>& rows) {
  const std::size_t D = L.dim, n = rows.size();
  std::vector<double> out(2 * D + (L.second_order ? D * D : 0), kNaN);
  const double c = ab_mean(L, rows), var = ab_variance(L, rows, c);
  if (!(var > 0)) return out;
  std::vector<double> s1(D, 0.0), st(D, 0.0), s2(D * D, 0.0);
  for (std::size_t r : rows) {
    const double* blk = &L.y[r * L.block];
    const double A = blk[0] - c, B = blk[L.block - 1] - c;
    for (std::size_t j = 0; j < D; ++j) {
      const double ABj = blk[1 + j] - c;
      s1[j] += B * (ABj - A);
      st[j] += (A - ABj) * (A - ABj);
      if (L.second_order)
        for (std::size_t k = j + 1; k < D; ++k) s2[j * D + k] += (blk[1 + D + j] - c) * (blk[1 + k] - c) - A * B;
    }
  }
  for (std::size_t j = 0; j < D; ++j) {
    out[j] = s1[j] / n / var;
    out[D + j] = st[j] / (2.0 * n) / var;
  }
  if (L.second_order)
    for (std::size_t j = 0; j < D; ++j)
      for (std::size_t k = j + 1; k < D; ++k) out[2 * D + j * D + k] = s2[j * D + k] / n / var - out[j] - out[k];
  return out;
}

// Blocks of `block` consecutive outputs whose values are all finite; counts the rest.
std::vector<std::size_t> finite_blocks(const std::vector<double>& y, std::size_t block, OutputCounts& c) {
  std::vector<std::size_t> keep;
  for (std::size_t i = 0; i < y.size() / block; ++i) {
    std::size_t bad = 0;
    for (std::size_t k = 0; k < block; ++k) bad += std::isfinite(y[i * block + k]) ? 0 : 1;
    c.n_nonfinite += bad;
    if (bad) ++c.n_dropped;
    else keep.push_back(i);
  }
  c.n_used = keep.size();
  return keep;
}

}  // namespace

double normal_quantile(double p) {
  if (!(p > 0 && p < 1)) throw Error("normal_quantile: p must lie in (0, 1), got " + std::to_string(p));
  double lo = -40, hi = 40;  // Phi(x) = erfc(-x/sqrt2)/2 is monotone; bisection to full precision
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

SobolIndices sobol_analyze(std::size_t dim, bool second_order, const std::vector<double>& y,
                           const BootstrapOptions& bootstrap) {
  check_bootstrap(bootstrap);
  const SobolLayout L{y, dim, second_order ? 2 * dim + 2 : dim + 2, second_order};
  if (dim == 0 || y.empty() || y.size() % L.block != 0)
    throw Error("sobol analysis: " + std::to_string(y.size()) + " outputs are not a whole number of blocks of " +
                std::to_string(L.block) + " (D = " + std::to_string(dim) + ")");
  SobolIndices s;
  const std::vector<std::size_t> rows = finite_blocks(y, L.block, s.counts);
  const std::size_t n_est = 2 * dim + (second_order ? dim * dim : 0);
  std::vector<double> est(n_est, kNaN), conf(n_est, kNaN);
  if (rows.size() >= 2) {
    est = sobol_estimate(L, rows);
    Spread spread(n_est);
    sweep::SplitMix64 rng{bootstrap.seed};
    for (std::size_t b = 0; b < bootstrap.resamples; ++b) spread.add(sobol_estimate(L, resample(rows, rng)));
    conf = spread.half_width(normal_quantile(0.5 + bootstrap.confidence / 2));
    s.variance = ab_variance(L, rows, ab_mean(L, rows));
  }
  auto slice = [&](const std::vector<double>& v, std::size_t from, std::size_t n) {
    return std::vector<double>(v.begin() + from, v.begin() + from + n);
  };
  s.S1 = slice(est, 0, dim), s.S1_conf = slice(conf, 0, dim);
  s.ST = slice(est, dim, dim), s.ST_conf = slice(conf, dim, dim);
  if (second_order) {
    s.S2 = slice(est, 2 * dim, dim * dim), s.S2_conf = slice(conf, 2 * dim, dim * dim);
    for (std::size_t j = 0; j < dim; ++j)
      for (std::size_t k = 0; k <= j; ++k) s.S2[j * dim + k] = s.S2_conf[j * dim + k] = kNaN;
  }
  return s;
}

namespace {

// Elementary effects of one trajectory, indexed by parameter; checks that the design moves
// every coordinate exactly once, by one step.
std::vector<double> trajectory_effects(const MorrisDesign& d, const std::vector<double>& y, std::size_t t) {
  const std::size_t D = d.dim, first = t * (D + 1);
  std::vector<double> ee(D, kNaN);
  for (std::size_t k = 0; k < D; ++k) {
    const double* x0 = &d.unit[(first + k) * D];
    const double* x1 = x0 + D;
    std::size_t moved = D, n_moved = 0;
    for (std::size_t j = 0; j < D; ++j)
      if (x1[j] != x0[j]) moved = j, ++n_moved;
    if (n_moved != 1 || !std::isnan(ee[moved]))
      throw Error("morris analysis: design rows " + std::to_string(first + k) + " and " + std::to_string(first + k + 1) +
                  " are not one step of a trajectory");
    const double step = x1[moved] > x0[moved] ? d.delta : -d.delta;
    ee[moved] = (y[first + k + 1] - y[first + k]) / step;
  }
  return ee;
}

}  // namespace

MorrisIndices morris_analyze(const MorrisDesign& d, const std::vector<double>& y, const BootstrapOptions& bootstrap) {
  check_bootstrap(bootstrap);
  if (y.size() != d.rows() || d.unit.size() != d.rows() * d.dim)
    throw Error("morris analysis: " + std::to_string(y.size()) + " outputs for a design of " +
                std::to_string(d.rows()) + " rows");
  const std::size_t D = d.dim;
  MorrisIndices m;
  const std::vector<std::size_t> used = finite_blocks(y, D + 1, m.counts);
  std::vector<std::vector<double>> ee(d.trajectories);
  for (std::size_t t : used) ee[t] = trajectory_effects(d, y, t);
  auto abs_mean = [&](const std::vector<std::size_t>& ts) {
    std::vector<double> out(D, 0.0);
    for (std::size_t t : ts)
      for (std::size_t j = 0; j < D; ++j) out[j] += std::fabs(ee[t][j]) / ts.size();
    return out;
  };
  m.mu.assign(D, kNaN), m.mu_star.assign(D, kNaN), m.sigma.assign(D, kNaN), m.mu_star_conf.assign(D, kNaN);
  if (used.size() < 2) return m;
  const double n = static_cast<double>(used.size());
  for (std::size_t j = 0; j < D; ++j) {
    double sum = 0, ss = 0;
    for (std::size_t t : used) sum += ee[t][j];
    m.mu[j] = sum / n;
    for (std::size_t t : used) ss += (ee[t][j] - m.mu[j]) * (ee[t][j] - m.mu[j]);
    m.sigma[j] = std::sqrt(ss / (n - 1));
  }
  m.mu_star = abs_mean(used);
  Spread spread(D);
  sweep::SplitMix64 rng{bootstrap.seed};
  for (std::size_t b = 0; b < bootstrap.resamples; ++b) spread.add(abs_mean(resample(used, rng)));
  m.mu_star_conf = spread.half_width(normal_quantile(0.5 + bootstrap.confidence / 2));
  return m;
}

}  // namespace phasmid::gsa
