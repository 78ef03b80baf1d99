#include "gsa/resolution.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace phasmid::gsa {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The size is solved for this fraction of the target half-width: intervals from a few base
// rows are themselves noisy, and an estimate aimed exactly at the target would often leave an
// index just above it at the size it names.
constexpr double kAim = 0.8;

bool sobol_resolved(double v, double conf, double h) {
  return std::isfinite(v) && std::isfinite(conf) && conf <= h && v >= -h / 2 && v <= 1 + h / 2;
}

// Half-width the subsets predict at size n: half-width = c / sqrt(n), the rate of a mean's
// bootstrap, with log c the mean of log(half-width_k) + log(n_k)/2 over the subsets that have
// one (so one noisy subset does not set the estimate). NaN without any.
double predicted_at(double n, const std::vector<std::size_t>& sizes, const std::vector<double>& conf) {
  double sum = 0, k = 0;
  for (std::size_t i = 0; i < sizes.size() && i < conf.size(); ++i) {
    if (!(std::isfinite(conf[i]) && conf[i] > 0)) continue;
    sum += std::log(conf[i]) + 0.5 * std::log(static_cast<double>(sizes[i]));
    k += 1;
  }
  return k > 0 ? std::exp(sum / k) / std::sqrt(n) : kNaN;
}

// Base size at which the half-width would shrink to `target`, from the subsets' half-widths
// (or, without them, from `conf` at size n alone); NaN when no half-width is finite.
double size_for(double n, double conf, double target, const std::vector<std::size_t>& sizes,
                const std::vector<double>& subset_conf) {
  if (!std::isfinite(conf)) return kNaN;
  if (conf <= target) return 2 * n;  // in range only by more rows than the bias shows now
  double at_n = predicted_at(n, sizes, subset_conf);
  if (!std::isfinite(at_n)) at_n = conf;
  const double aim = kAim * target;
  return n * (at_n / aim) * (at_n / aim);
}

// Bookkeeping of one feature's unresolved indices and the largest size they ask for.
struct Tally {
  FeatureResolution& out;
  bool unknown = false;
  double largest = 0;
  void add(bool resolved, double needed) {
    if (resolved) return;
    ++out.n_unresolved;
    if (std::isnan(needed)) unknown = true;
    else largest = std::max(largest, needed);
  }
};

// Subset half-widths of parameter j, from the convergence rows of `levels`.
template <class Indices>
std::vector<double> subset_conf(const std::vector<Indices>& levels, std::vector<double> Indices::*field, std::size_t j) {
  std::vector<double> c;
  for (const Indices& x : levels) c.push_back(j < (x.*field).size() ? (x.*field)[j] : kNaN);
  return c;
}

void resolve_sobol(const GsaResult& r, const FeatureResult& f, Tally& t) {
  const SobolIndices& s = f.sobol;
  const double h = r.resolution, n = static_cast<double>(r.saltelli.n_base);
  const std::size_t D = r.parameters.size();
  auto one = [&](double v, double conf, const std::vector<double>& subsets, std::vector<char>& flags) {
    const bool ok = sobol_resolved(v, conf, h);
    const bool in_range = v >= -h / 2 && v <= 1 + h / 2;
    flags.push_back(ok);
    t.add(ok, size_for(n, conf, in_range ? h : h / 2, f.convergence_n, subsets));
  };
  for (std::size_t j = 0; j < D; ++j) {
    one(s.S1[j], s.S1_conf[j], subset_conf(f.sobol_convergence, &SobolIndices::S1_conf, j), t.out.S1);
    one(s.ST[j], s.ST_conf[j], subset_conf(f.sobol_convergence, &SobolIndices::ST_conf, j), t.out.ST);
  }
  if (s.S2.empty()) return;
  for (std::size_t i = 0; i < D * D; ++i) {
    if (i / D >= i % D) t.out.S2.push_back(1);  // the lower triangle and diagonal hold no index
    else one(s.S2[i], s.S2_conf[i], {}, t.out.S2);  // no subsets of S2 are kept
  }
  for (char ok : t.out.S2) t.out.n_unresolved_s2 += ok ? 0 : 1;
}

void resolve_morris(const GsaResult& r, const FeatureResult& f, Tally& t) {
  const MorrisIndices& m = f.morris;
  double top = 0;
  for (double v : m.mu_star)
    if (std::isfinite(v)) top = std::max(top, v);
  const double target = r.resolution * top, n = static_cast<double>(r.morris.trajectories);
  for (std::size_t j = 0; j < m.mu_star.size(); ++j) {
    const double conf = m.mu_star_conf[j];
    const bool ok = std::isfinite(m.mu_star[j]) && std::isfinite(conf) && conf <= target;
    t.out.mu_star.push_back(ok);
    const std::vector<double> subsets = subset_conf(f.morris_convergence, &MorrisIndices::mu_star_conf, j);
    t.add(ok, target > 0 ? size_for(n, conf, target, f.convergence_n, subsets) : kNaN);
  }
}

}  // namespace

std::string resolution_error(double threshold) {
  if (std::isfinite(threshold) && threshold > 0 && threshold <= 1) return "";
  return "resolution must be in (0, 1] (the largest interval half-width of a resolved index, e.g. 0.1)";
}

FeatureResolution resolve(const GsaResult& r, const FeatureResult& f) {
  FeatureResolution out;
  Tally t{out};
  if (r.method == "sobol") resolve_sobol(r, f, t);
  else resolve_morris(r, f, t);
  if (out.all_resolved()) return out;
  if (t.unknown || !(t.largest > 0)) {
    out.n_to_resolve = kNaN;
    return out;
  }
  out.n_to_resolve = std::exp2(std::ceil(std::log2(t.largest)));
  return out;
}

}  // namespace phasmid::gsa
