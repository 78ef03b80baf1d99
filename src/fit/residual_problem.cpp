#include "fit/residual_problem.hpp"

namespace phasmid::fit {

std::vector<std::string> ResidualProblem::parameter_names() const {
  std::vector<std::string> n;
  for (auto& p : est_) n.push_back(p.id);
  return n;
}

std::vector<double> ResidualProblem::start() const {
  std::vector<double> x;
  for (auto& p : est_) x.push_back(to_scaled(p.scale, p.nominal));
  return x;
}
std::vector<double> ResidualProblem::lower() const {
  std::vector<double> x;
  for (auto& p : est_) x.push_back(to_scaled(p.scale, p.lower));
  return x;
}
std::vector<double> ResidualProblem::upper() const {
  std::vector<double> x;
  for (auto& p : est_) x.push_back(to_scaled(p.scale, p.upper));
  return x;
}
std::vector<double> ResidualProblem::to_linear(const std::vector<double>& x) const {
  std::vector<double> t;
  for (size_t j = 0; j < est_.size(); ++j) t.push_back(from_scaled(est_[j].scale, x[j]));
  return t;
}

}  // namespace phasmid::fit
