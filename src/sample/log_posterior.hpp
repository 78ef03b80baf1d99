#pragma once
// The target of the samplers: the posterior of a fit's estimated parameters on their scales,
// log p(x | data) = log prior(x) + log L(x) + const, with log L = -1/2 sum r_i(x)^2 from the
// problem's weighted residuals. That is the Gaussian log-likelihood only when each residual is
// (model - data) / sigma with the true noise sigma, which a fit declares with
// `absolute_sigma = true` (estimated noises add their n ln sigma as residuals of their own;
// docs/recordings.md); the sampling verb refuses a fit without it. The constant (the Gaussian's
// normalisation of the fixed noises) is left out. Evaluations are const and may run
// concurrently, as the problem's do.
#include <vector>

#include "fit/residual_problem.hpp"

namespace phasmid::sample {

struct PosteriorValue {
  double log_prior = 0.0;       // -inf outside the bounds or the prior's support
  double log_likelihood = 0.0;  // -inf where the model run failed
  bool failed = false;          // the model run failed (counted by the samplers)
  // The tempered posterior of inverse temperature beta (1: the posterior itself).
  double tempered(double beta) const;
};

class LogPosterior {
 public:
  explicit LogPosterior(const fit::ResidualProblem& problem) : problem_(problem) {}
  size_t dim() const { return problem_.num_parameters(); }
  const fit::ResidualProblem& problem() const { return problem_; }
  double log_prior(const std::vector<double>& x) const;
  // Evaluates the model only where the prior is positive.
  PosteriorValue operator()(const std::vector<double>& x) const;

 private:
  const fit::ResidualProblem& problem_;
};

}  // namespace phasmid::sample
