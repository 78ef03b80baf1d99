#include "fit/uncertainty.hpp"

#include <cmath>
#include <limits>

#include "common/error.hpp"

namespace phasmid::fit {
namespace {
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();
}  // namespace

Uncertainty estimate_uncertainty(const ResidualProblem& problem, const std::vector<double>& x, bool absolute_sigma) {
  Uncertainty u;
  const size_t n = problem.num_parameters(), m = problem.num_residuals();
  u.standard_error_scaled = Eigen::VectorXd::Constant(n, kNaN);
  u.standard_error = Eigen::VectorXd::Constant(n, kNaN);
  u.correlation = Eigen::MatrixXd::Constant(n, n, kNaN);
  u.covariance_scaled = Eigen::MatrixXd::Constant(n, n, kNaN);
  std::vector<double> r(m), J(m * n);
  std::string err;
  if (!problem.has_jacobian()) {
    if (problem.evaluate(x.data(), r.data(), nullptr, &err)) u.residuals = Eigen::Map<Eigen::VectorXd>(r.data(), m);
    u.sigma2 = kNaN;
    u.message = "no standard errors: " + problem.no_jacobian_reason();
    return u;
  }
  if (!problem.evaluate(x.data(), r.data(), J.data(), &err)) {
    u.message = "no Jacobian at the optimum: " + err;
    return u;
  }
  u.residuals = Eigen::Map<Eigen::VectorXd>(r.data(), m);
  u.jacobian = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(J.data(), m, n);
  const double cost = 0.5 * u.residuals.squaredNorm();
  if (absolute_sigma) {
    u.sigma2 = 1.0;
  } else if (m > n) {
    u.sigma2 = 2.0 * cost / static_cast<double>(m - n);
  } else {
    u.sigma2 = kNaN;
    u.message = "as many parameters as residuals: no residual variance (set absolute_sigma = true to use the tolerances)";
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(u.jacobian, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd sv = svd.singularValues();
  const double tol = std::max<double>(m, n) * std::numeric_limits<double>::epsilon() * (sv.size() ? sv[0] : 0.0) * 1e3;
  u.rank = 0;
  Eigen::VectorXd inv2 = Eigen::VectorXd::Zero(sv.size());
  for (int i = 0; i < sv.size(); ++i)
    if (sv[i] > tol) {
      ++u.rank;
      inv2[i] = 1.0 / (sv[i] * sv[i]);
    }
  const Eigen::MatrixXd& V = svd.matrixV();
  u.covariance_scaled = u.sigma2 * V * inv2.asDiagonal() * V.transpose();
  // A parameter with a component along a null direction of J is not determined.
  std::vector<bool> undetermined(n, false);
  for (int i = 0; i < sv.size(); ++i)
    if (!(sv[i] > tol))
      for (size_t j = 0; j < n; ++j)
        if (std::abs(V(j, i)) > 1e-8) undetermined[j] = true;
  for (size_t j = 0; j < n; ++j) {
    double se = undetermined[j] ? kInf : std::sqrt(u.covariance_scaled(j, j));
    u.standard_error_scaled[j] = se;
    u.standard_error[j] = std::abs(dtheta_dx(problem.estimated()[j].scale, x[j])) * se;
  }
  for (size_t a = 0; a < n; ++a)
    for (size_t b = 0; b < n; ++b)
      if (!undetermined[a] && !undetermined[b])
        u.correlation(a, b) = u.covariance_scaled(a, b) /
                              std::sqrt(u.covariance_scaled(a, a) * u.covariance_scaled(b, b));
  u.ok = u.rank == static_cast<int>(n) && std::isfinite(u.sigma2);
  if (u.rank < static_cast<int>(n))
    u.message = "the Jacobian has rank " + std::to_string(u.rank) + " < " + std::to_string(n) +
                ": some parameters are not determined by the targets (infinite standard error)";
  return u;
}

std::vector<double> profile_grid(const ResidualProblem& problem, const std::vector<double>& x_opt, size_t j,
                                 const Eigen::VectorXd& se_scaled, size_t points, double span) {
  const auto lo = problem.lower(), hi = problem.upper();
  if (points < 3) points = 3;
  if (points % 2 == 0) ++points;
  double a = lo[j], b = hi[j];
  if (std::isfinite(se_scaled[j]) && se_scaled[j] > 0) {
    a = std::max(lo[j], x_opt[j] - span * se_scaled[j]);
    b = std::min(hi[j], x_opt[j] + span * se_scaled[j]);
  }
  const size_t half = points / 2;
  std::vector<double> grid(points);
  for (size_t i = 0; i < half; ++i) grid[i] = a + (x_opt[j] - a) * i / half;
  grid[half] = x_opt[j];
  for (size_t i = 1; i <= half; ++i) grid[half + i] = x_opt[j] + (b - x_opt[j]) * i / half;
  return grid;
}

Profile empty_profile(const ResidualProblem& problem, size_t j, size_t points) {
  Profile pr;
  pr.parameter = problem.estimated().at(j).id;
  pr.values.resize(points);
  pr.cost.assign(points, kNaN);
  pr.delta_chi2.assign(points, kNaN);
  pr.converged.assign(points, 0);
  return pr;
}

std::vector<size_t> profile_side(int dir, size_t points) {
  const size_t half = points / 2;
  std::vector<size_t> idx;
  for (size_t step = (dir < 0 ? 0 : 1); step <= half; ++step) idx.push_back(dir < 0 ? half - step : half + step);
  return idx;
}

void profile_walk(const ResidualProblem& problem, const std::vector<double>& x_opt, double cost_opt, size_t j,
                  double sigma2, const std::vector<double>& grid, int dir, OptimizerOptions o, Profile& pr) {
  o.method = "ceres";  // profiles re-optimise with exact Jacobians and held parameters
  o.fixed = {j};
  o.progress = false;
  const double s2 = std::isfinite(sigma2) && sigma2 > 0 ? sigma2 : 1.0;
  std::vector<double> x = x_opt;
  for (size_t i : profile_side(dir, grid.size())) {
    x[j] = grid[i];
    FitSummary s = optimize(problem, x, o);
    pr.values[i] = from_scaled(problem.estimated()[j].scale, grid[i]);
    if (s.usable) {
      pr.cost[i] = s.final_cost;
      pr.delta_chi2[i] = 2.0 * (s.final_cost - cost_opt) / s2;
      pr.converged[i] = s.converged ? 1 : 0;
      x = s.x;
    }
  }
}

Profile profile_likelihood(const ResidualProblem& problem, const std::vector<double>& x_opt, double cost_opt, size_t j,
                           double sigma2, const Eigen::VectorXd& se_scaled, size_t points, double span,
                           OptimizerOptions o) {
  const std::vector<double> grid = profile_grid(problem, x_opt, j, se_scaled, points, span);
  Profile pr = empty_profile(problem, j, grid.size());
  for (int dir : {-1, +1}) profile_walk(problem, x_opt, cost_opt, j, sigma2, grid, dir, o, pr);
  return pr;
}

}  // namespace phasmid::fit
