#pragma once
// Optimiser back ends (Ceres' "Solver::Options" / "Solver::Summary" shape):
//  - "ceres": Levenberg-Marquardt trust region with bounds, exact Jacobians from forward
//    sensitivities, optional robust loss;
//  - "nlopt:NAME": local derivative-free, local gradient-based (the same exact gradient J^T r)
//    and global NLopt methods.
// All minimise cost = 1/2 sum r^2 over the scaled parameters within their bounds. Which
// optimisers exist is the table optimizers() (optimizer.cpp): the parser, the checks and their
// error messages, the back-end dispatch and the `--optimizer` help all read it, so adding an
// optimiser is adding one row. Every optimiser honours the box bounds; none takes nonlinear
// constraints (a fit has none).
// A failing fit (simulation failures, no convergence, parameters at bounds) is reported in
// the summary, never thrown.
#include <string>
#include <vector>

#include "fit/residual_problem.hpp"

namespace phasmid::fit {

enum class Backend { Ceres, NLopt };

struct OptimizerInfo {
  std::string name;                  // as --optimizer takes it: "ceres", "nlopt:BOBYQA"
  Backend backend;
  int nlopt_algorithm;               // NLopt's nlopt_algorithm value (NLopt rows; -1 otherwise)
  bool needs_gradient;               // evaluates Jacobians: refused for problems without them
  bool global;                       // searches the whole box; the evaluation budget stops it
  bool seeded;                       // randomised: seeded so that a fit repeats exactly
  bool robust_loss;                  // applies the `loss` per residual
  std::string local;                 // the local optimiser a multi-level method runs, or ""
  std::vector<std::string> aliases;  // other accepted spellings (case-insensitive)
  std::string description;           // one line for --help
};

const std::vector<OptimizerInfo>& optimizers();
// The row of a spelling ("nlopt:bobyqa", "nlopt:LN_BOBYQA", an alias). Throws Error
// "unknown optimizer 'x' (expected one of ceres, nlopt:BOBYQA, ...)".
const OptimizerInfo& find_optimizer(const std::string& spec);
// "ceres, nlopt:BOBYQA, ...": the names of the rows `keep` accepts (all rows without it).
std::string optimizer_list(bool (*keep)(const OptimizerInfo&) = nullptr);
// The `--optimizer` help: one line per row with its kind and description.
std::string optimizer_help();

struct OptimizerOptions {
  std::string method = "ceres";            // a name of optimizers()
  int max_iterations = 100;                // Ceres iterations
  int max_evaluations = 2000;              // NLopt objective evaluations
  double function_tolerance = 1e-10;       // relative change of the cost
  double parameter_tolerance = 1e-10;      // relative change of x
  double gradient_tolerance = 1e-12;
  double initial_trust_region_radius = 1e4;  // Ceres; small values make the first LM steps cautious
  std::string loss = "none";               // none | huber | cauchy | soft_l1 | arctan (optimizers with robust_loss)
  double loss_scale = 1.0;                 // in residual units (i.e. tolerances / sigmas)
  bool numeric_jacobian = false;           // Ceres central differences instead of sensitivities (benchmark baseline)
  std::vector<size_t> fixed;               // indices of x held at their start value (profiles; Ceres only)
  bool progress = false;                   // progress line on stderr (only if it is a terminal)
  std::string progress_label = "fit";
};

// Sets options.method to the row find_optimizer(spec) names; throws as find_optimizer.
void parse_optimizer(const std::string& spec, OptimizerOptions& options);
const OptimizerInfo& optimizer_info(const OptimizerOptions& options);
// True for the optimisers that need the Jacobian (the table's needs_gradient).
bool needs_jacobian(const OptimizerOptions& options);
// Throws Error (one line) if the optimiser needs a Jacobian the problem cannot provide:
// "optimizer ceres needs a gradient but the model has none: <reason>; use one of ...".
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
