#pragma once
// The proposal of one chain (or one temperature of a tempered chain): adaptive Metropolis
// (Haario, Saksman & Tamminen 2001) with the global scale adaptation of Andrieu & Thoms (2008,
// Algorithm 4), as pyPESTO's AdaptiveMetropolisSampler runs it. Proposals are
// y = x + sqrt(s) L z, z ~ N(0, I), L L^T = C + eps I; after each step the running mean and
// covariance C take in the chain's state with weight gamma_t = (t + t0)^-decay, and
// log s += gamma_t (alpha_t - target), alpha_t the step's acceptance probability, so that the
// acceptance rate settles at the target (0.234, optimal for Gaussian targets in many
// dimensions, Roberts, Gelman & Gilks 1997). gamma_t -> 0 (diminishing adaptation) keeps the
// chain's limit the target distribution. t0 is the weight of the initial covariance, in steps.
#include <random>

#include <Eigen/Dense>

namespace phasmid::sample {

struct AdaptiveMetropolisOptions {
  double target_acceptance = 0.234;
  double decay = 0.51;             // in (0.5, 1]: the step sizes' sum diverges, their squares' not
  double initial_weight = 100.0;   // t0, in steps
  double regularisation = 1e-10;   // eps, relative to the covariance's mean diagonal
  bool IsValid(std::string* why) const;
};

class AdaptiveMetropolis {
 public:
  // cov0: the initial proposal covariance (positive semi-definite, n x n), which the
  // adaptation starts from; it is scaled by 2.38^2 / n (Gelman, Roberts & Gilks 1996).
  AdaptiveMetropolis(const Eigen::VectorXd& x0, const Eigen::MatrixXd& cov0, const AdaptiveMetropolisOptions& o);

  Eigen::VectorXd propose(const Eigen::VectorXd& x, std::mt19937_64& rng) const;
  // After a step: x is the chain's state after it, alpha the step's acceptance probability.
  void adapt(const Eigen::VectorXd& x, double alpha);
  double scale() const { return scale_; }

 private:
  void factorise();
  AdaptiveMetropolisOptions o_;
  Eigen::VectorXd mean_;
  Eigen::MatrixXd cov_, chol_;
  double scale_;
  double steps_ = 0;
};

}  // namespace phasmid::sample
