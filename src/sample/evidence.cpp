#include "sample/evidence.hpp"

#include <cmath>

#include "sample/diagnostics.hpp"

namespace phasmid::sample {

double Evidence::error() const { return std::hypot(mc_error, discretisation_error); }

namespace {
struct Level {
  double beta, mean, var, var_of_mean;  // of log L at the level: var is d mean / d beta
};

// Trapezoid over levels ordered coldest (beta = 1) to hottest (beta = 0), every `stride`-th
// level from the hottest, the coldest always included, with the Euler-Maclaurin correction
// -h^2/12 (f'(b) - f'(a)) whose derivatives f' = Var_beta[log L] each level measures (Friel,
// Hurn & Wyse 2014); adds the Monte Carlo variance of the means.
double trapezoid(const std::vector<Level>& l, std::size_t stride, double* var) {
  std::vector<std::size_t> idx;
  for (std::size_t k = l.size() - 1;; k = k >= stride ? k - stride : 0) {
    idx.push_back(k);
    if (k == 0) break;
  }
  std::vector<double> w(l.size(), 0.0);
  double sum = 0;
  for (std::size_t i = 0; i + 1 < idx.size(); ++i) {
    const Level &a = l[idx[i]], &b = l[idx[i + 1]];
    const double h = b.beta - a.beta;
    sum += 0.5 * h * (a.mean + b.mean) - h * h / 12.0 * (b.var - a.var);
    w[idx[i]] += 0.5 * h, w[idx[i + 1]] += 0.5 * h;
  }
  if (var)
    for (std::size_t k = 0; k < l.size(); ++k) *var += w[k] * w[k] * l[k].var_of_mean;
  return sum;
}

std::vector<Level> levels_of(const SamplerResult& r, std::size_t c, std::size_t from) {
  std::vector<Level> out;
  for (std::size_t k = 0; k < r.temperatures; ++k) {
    const double* ll = &r.level_log_likelihood[(c * r.temperatures + k) * r.draws];
    const std::vector<double> kept(ll + from, ll + r.draws);
    const Moments mo = moments(kept);
    const double ess = effective_sample_size({kept});
    out.push_back({r.betas[c * r.temperatures + k], mo.mean, mo.variance, std::isfinite(ess) && ess > 0 ? mo.variance / ess : 0.0});
  }
  return out;
}
}  // namespace

Evidence thermodynamic_integration(const SamplerResult& r, std::size_t from) {
  Evidence e;
  // The ladder's adaptation never moves the hottest level, so a prior level stays at beta = 0.
  if (!r.prior_level || r.level_log_likelihood.empty()) {
    e.note = "thermodynamic integration needs tempered levels and a prior level at beta = 0 ([sample] evidence = true)";
    return e;
  }
  if (r.draws < from + 4) {
    e.note = "no draws left after the burn-in and the ladder's adaptation";
    return e;
  }
  double full = 0, half = 0, var = 0;
  e.mean_log_likelihood.assign(r.temperatures, 0.0);
  for (std::size_t c = 0; c < r.chains; ++c) {
    const std::vector<Level> l = levels_of(r, c, from);
    full += trapezoid(l, 1, &var);
    half += trapezoid(l, 2, nullptr);
    for (std::size_t k = 0; k < l.size(); ++k) e.mean_log_likelihood[k] += l[k].mean / double(r.chains);
    if (c == 0)
      for (const Level& x : l) e.betas.push_back(x.beta);
  }
  e.log_evidence = full / double(r.chains);
  // The corrected rule's error falls as h^4: over every other level it is 16 times the
  // full ladder's, so their difference is 15 times it (Richardson).
  e.discretisation_error = std::abs(full - half) / 15.0 / double(r.chains);
  e.mc_error = std::sqrt(var) / double(r.chains);
  e.ok = std::isfinite(e.log_evidence);
  if (!e.ok) e.note = "a level's mean log-likelihood is not finite (failed model runs at the prior?)";
  return e;
}

}  // namespace phasmid::sample
