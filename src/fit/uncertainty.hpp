#pragma once
// Standard errors and correlations from the Jacobian at the optimum (Gauss-Newton /
// Fisher information): Cov(x) = s^2 (J^T J)^{-1} in the scaled parameters, with
// s^2 = 2 cost / (m - n) (residual variance; the weights' scale is estimated) or s^2 = 1
// (absolute_sigma: tolerances / sigmas are the true noise). Standard errors on the linear
// scale by the delta method, SE(theta_j) = |d theta_j / d x_j| SE(x_j). Directions the data
// do not determine (singular J^T J) get an infinite standard error.
// Profile likelihood: the cost minimised over the other parameters with one held fixed on
// a grid; delta_chi2 = 2 (cost - cost_min) / s^2, compared with 3.84 (95 %, 1 dof).
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fit/optimizer.hpp"

namespace phasmid::fit {

struct Uncertainty {
  bool ok = false;
  std::string message;
  double sigma2 = 1;                     // s^2
  Eigen::MatrixXd covariance_scaled;     // n x n in x
  Eigen::VectorXd standard_error_scaled; // in x
  Eigen::VectorXd standard_error;        // linear scale, parameter units
  Eigen::MatrixXd correlation;           // n x n (NaN where undefined)
  Eigen::VectorXd residuals;             // at the optimum
  Eigen::MatrixXd jacobian;              // m x n at the optimum (scaled x)
  int rank = 0;
};

Uncertainty estimate_uncertainty(const ResidualProblem& problem, const std::vector<double>& x, bool absolute_sigma);

struct Profile {
  std::string parameter;
  std::vector<double> values;      // linear scale
  std::vector<double> cost;        // NaN where the inner fit failed
  std::vector<double> delta_chi2;
  std::vector<int> converged;      // 1/0
};

// points: grid size (odd; includes the optimum); span: +- span standard errors of x (clipped
// to the bounds; the whole range when the standard error is not finite).
Profile profile_likelihood(const ResidualProblem& problem, const std::vector<double>& x_opt, double cost_opt, size_t j,
                           double sigma2, const Eigen::VectorXd& se_scaled, size_t points, double span,
                           OptimizerOptions options);

// The pieces of profile_likelihood, for running its two halves as separate tasks: each half
// walks outward from the optimum, warm-starting each point from its neighbour, and depends
// only on the optimum and the grid, so the halves give the same numbers wherever they run.
std::vector<double> profile_grid(const ResidualProblem& problem, const std::vector<double>& x_opt, size_t j,
                                 const Eigen::VectorXd& se_scaled, size_t points, double span);  // scaled
Profile empty_profile(const ResidualProblem& problem, size_t j, size_t points);
std::vector<size_t> profile_side(int dir, size_t points);  // grid indices of a half: -1 below and at the optimum, +1 above
void profile_walk(const ResidualProblem& problem, const std::vector<double>& x_opt, double cost_opt, size_t j,
                  double sigma2, const std::vector<double>& grid, int dir, OptimizerOptions options, Profile& pr);

}  // namespace phasmid::fit
