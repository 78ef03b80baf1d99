#pragma once
// Optimiser back ends (Ceres' "Solver::Options" / "Solver::Summary" shape):
//  - "ceres": Levenberg-Marquardt trust region with bounds, exact Jacobians from forward
//    sensitivities, optional robust loss;
//  - "nlopt:NAME": local derivative-free (BOBYQA, COBYLA, NELDERMEAD, SBPLX), gradient-based
//    with the same exact gradient J^T r (LBFGS, SLSQP, MMA), global (DIRECT_L, CRS2_LM,
//    ISRES, MLSL). All minimise cost = 1/2 sum r^2 over the scaled parameters.
// A failing fit (simulation failures, no convergence, parameters at bounds) is reported in
// the summary, never thrown.
#include <string>
#include <vector>

#include "fit/residual_problem.hpp"

namespace phasmid::fit {

enum class Backend { Ceres, NLopt };

struct OptimizerOptions {
  Backend backend = Backend::Ceres;
  std::string nlopt_algorithm = "BOBYQA";  // upper case NLopt name without the LN_/LD_/GN_ prefix
  int max_iterations = 100;                // Ceres iterations
  int max_evaluations = 2000;              // NLopt objective evaluations
  double function_tolerance = 1e-10;       // relative change of the cost
  double parameter_tolerance = 1e-10;      // relative change of x
  double gradient_tolerance = 1e-12;
  double initial_trust_region_radius = 1e4;  // Ceres; small values make the first LM steps cautious
  std::string loss = "none";               // none | huber | cauchy | soft_l1 | arctan (Ceres only)
  double loss_scale = 1.0;                 // in residual units (i.e. tolerances / sigmas)
  bool numeric_jacobian = false;           // Ceres central differences instead of sensitivities (benchmark baseline)
  std::vector<size_t> fixed;               // indices of x held at their start value (profiles; Ceres only)
  bool progress = false;                   // progress line on stderr (only if it is a terminal)
  std::string progress_label = "fit";
};

// "ceres" or "nlopt:NAME" (case-insensitive). Throws Error naming the accepted values.
void parse_optimizer(const std::string& spec, OptimizerOptions& options);
std::string optimizer_name(const OptimizerOptions& options);
std::vector<std::string> nlopt_algorithms();
// True for the back ends that need the Jacobian: ceres and the gradient-based NLopt methods.
bool needs_jacobian(const OptimizerOptions& options);
// Throws Error (one line) if the optimiser needs a Jacobian the problem cannot provide.
void check_optimizer(const ResidualProblem& problem, const OptimizerOptions& options);

struct FitSummary {
  bool converged = false;      // the back end reports convergence (not: iteration limit or failure)
  bool usable = false;         // a finite cost was reached (converged or not)
  std::string optimizer;       // "ceres" / "nlopt:BOBYQA"
  std::string termination;     // back end's termination type
  std::string message;         // back end's message, plus the last evaluation failure if any
  std::vector<double> x_start, x;  // scaled
  double initial_cost = 0, final_cost = 0;
  int iterations = 0;
  long evaluations = 0, jacobian_evaluations = 0, failed_evaluations = 0;
  std::vector<double> cost_history;  // Ceres: cost per iteration; NLopt: best cost after each evaluation that improved it
  std::vector<std::string> at_bound;  // estimated parameters ending within 1e-6 of a bound
  double wall_seconds = 0;
  std::string report;          // Ceres FullReport / NLopt result text
};

FitSummary optimize(const ResidualProblem& problem, const std::vector<double>& x0, const OptimizerOptions& options);

// Back ends (used by optimize()).
FitSummary optimize_ceres(const ResidualProblem& problem, const std::vector<double>& x0, const OptimizerOptions& options);
FitSummary optimize_nlopt(const ResidualProblem& problem, const std::vector<double>& x0, const OptimizerOptions& options);

// One-paragraph human summary (several short lines).
std::string describe(const ResidualProblem& problem, const FitSummary& s);

}  // namespace phasmid::fit
