#include "sample/adaptive_metropolis.hpp"

#include <cmath>
#include <string>

namespace phasmid::sample {

bool AdaptiveMetropolisOptions::IsValid(std::string* why) const {
  auto fail = [&](const char* m) {
    if (why) *why = m;
    return false;
  };
  if (!(target_acceptance > 0 && target_acceptance < 1)) return fail("target acceptance must lie in (0, 1)");
  if (!(decay > 0.5 && decay <= 1)) return fail("adaptation decay must lie in (0.5, 1]");
  if (!(initial_weight >= 1)) return fail("initial weight must be at least 1 step");
  if (!(regularisation > 0)) return fail("regularisation must be positive");
  return true;
}

AdaptiveMetropolis::AdaptiveMetropolis(const Eigen::VectorXd& x0, const Eigen::MatrixXd& cov0,
                                       const AdaptiveMetropolisOptions& o)
    : o_(o), mean_(x0), cov_(cov0), scale_(2.38 * 2.38 / static_cast<double>(x0.size())) {
  factorise();
}

void AdaptiveMetropolis::factorise() {
  const Eigen::Index n = cov_.rows();
  const double level = std::max(cov_.diagonal().mean(), 1e-300);
  Eigen::MatrixXd c = cov_ + o_.regularisation * level * Eigen::MatrixXd::Identity(n, n);
  Eigen::LLT<Eigen::MatrixXd> llt(c);
  if (llt.info() == Eigen::Success) {
    chol_ = llt.matrixL();
  } else {  // rounding made C indefinite: its diagonal still gives a usable proposal
    chol_ = c.diagonal().cwiseMax(1e-300).cwiseSqrt().asDiagonal();
  }
}

Eigen::VectorXd AdaptiveMetropolis::propose(const Eigen::VectorXd& x, std::mt19937_64& rng) const {
  std::normal_distribution<double> normal;
  Eigen::VectorXd z(x.size());
  for (Eigen::Index i = 0; i < z.size(); ++i) z[i] = normal(rng);
  return x + std::sqrt(scale_) * (chol_ * z);
}

void AdaptiveMetropolis::adapt(const Eigen::VectorXd& x, double alpha) {
  steps_ += 1;
  const double gamma = std::pow(steps_ + o_.initial_weight, -o_.decay);
  mean_ += gamma * (x - mean_);
  const Eigen::VectorXd d = x - mean_;
  cov_ = (1 - gamma) * cov_ + gamma * d * d.transpose();
  scale_ *= std::exp(gamma * (alpha - o_.target_acceptance));
  factorise();
}

}  // namespace phasmid::sample
