#include "sample/log_posterior.hpp"

#include <cmath>
#include <limits>

namespace phasmid::sample {

double PosteriorValue::tempered(double beta) const {
  // log_prior is -inf outside the bounds even for beta = 0, where the likelihood drops out.
  if (!std::isfinite(log_prior) || !std::isfinite(log_likelihood)) return -std::numeric_limits<double>::infinity();
  return log_prior + beta * log_likelihood;
}

double LogPosterior::log_prior(const std::vector<double>& x) const {
  double lp = 0.0;
  const auto& est = problem_.estimated();
  for (size_t j = 0; j < est.size(); ++j)
    lp += fit::log_prior_density(est[j].prior, est[j].scale, est[j].lower, est[j].upper, x[j]);
  return lp;
}

PosteriorValue LogPosterior::operator()(const std::vector<double>& x) const {
  const double inf = std::numeric_limits<double>::infinity();
  PosteriorValue v;
  v.log_prior = log_prior(x);
  if (!std::isfinite(v.log_prior)) {
    v.log_likelihood = -inf;
    return v;
  }
  std::vector<double> r(problem_.num_residuals());
  if (!problem_.evaluate(x.data(), r.data(), nullptr)) {
    v.failed = true;
    v.log_likelihood = -inf;
    return v;
  }
  double ss = 0.0;
  for (double ri : r) ss += ri * ri;
  v.log_likelihood = std::isfinite(ss) ? -0.5 * ss : -inf;
  v.failed = !std::isfinite(ss);
  return v;
}

}  // namespace phasmid::sample
