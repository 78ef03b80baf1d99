#include "fit/optimizer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "common/error.hpp"

namespace phasmid::fit {

std::vector<std::string> nlopt_algorithms() {
  return {"BOBYQA", "COBYLA", "NELDERMEAD", "SBPLX", "LBFGS", "SLSQP", "MMA", "DIRECT_L", "CRS2_LM", "ISRES", "MLSL"};
}

void parse_optimizer(const std::string& spec, OptimizerOptions& o) {
  std::string s = spec;
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  if (s == "ceres") {
    o.backend = Backend::Ceres;
    return;
  }
  if (s.rfind("nlopt:", 0) == 0 || s == "nlopt") {
    std::string name = s == "nlopt" ? "bobyqa" : s.substr(6);
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::toupper(c); });
    for (const char* pre : {"LN_", "LD_", "GN_", "GD_", "G_"})
      if (name.rfind(pre, 0) == 0) name = name.substr(std::string(pre).size());
    if (name == "NELDER_MEAD") name = "NELDERMEAD";
    if (name == "DIRECT-L" || name == "DIRECTL") name = "DIRECT_L";
    if (name == "CRS2" || name == "CRS") name = "CRS2_LM";
    if (name == "MLSL_LDS") name = "MLSL";
    auto all = nlopt_algorithms();
    if (std::find(all.begin(), all.end(), name) == all.end()) {
      std::string list;
      for (auto& a : all) list += (list.empty() ? "" : ", ") + a;
      throw Error("unknown NLopt algorithm '" + spec.substr(std::min<size_t>(6, spec.size())) + "' (expected one of " + list + ")");
    }
    o.backend = Backend::NLopt;
    o.nlopt_algorithm = name;
    return;
  }
  throw Error("unknown optimizer '" + spec + "' (expected ceres or nlopt:NAME, e.g. nlopt:BOBYQA)");
}

std::string optimizer_name(const OptimizerOptions& o) {
  return o.backend == Backend::Ceres ? std::string("ceres") : "nlopt:" + o.nlopt_algorithm;
}

bool needs_jacobian(const OptimizerOptions& o) {
  if (o.backend == Backend::Ceres) return true;
  for (const char* g : {"LBFGS", "SLSQP", "MMA", "MLSL"})
    if (o.nlopt_algorithm == g) return true;
  return false;
}

void check_optimizer(const ResidualProblem& problem, const OptimizerOptions& o) {
  if (problem.has_jacobian() || !needs_jacobian(o)) return;
  throw Error("optimizer " + optimizer_name(o) + " needs Jacobians, which this fit problem does not provide (" +
              problem.no_jacobian_reason() + "); use a derivative-free or global NLopt method: nlopt:BOBYQA, " +
              "nlopt:COBYLA, nlopt:NELDERMEAD, nlopt:SBPLX, nlopt:DIRECT_L, nlopt:CRS2_LM or nlopt:ISRES");
}

FitSummary optimize(const ResidualProblem& problem, const std::vector<double>& x0, const OptimizerOptions& o) {
  check_optimizer(problem, o);
  if (x0.size() != problem.num_parameters()) throw Error("internal: start vector has the wrong size");
  auto t0 = std::chrono::steady_clock::now();
  FitSummary s = o.backend == Backend::Ceres ? optimize_ceres(problem, x0, o) : optimize_nlopt(problem, x0, o);
  s.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  s.optimizer = optimizer_name(o);
  s.x_start = x0;
  const auto lo = problem.lower(), hi = problem.upper();
  for (size_t j = 0; j < s.x.size(); ++j) {
    const double tol = 1e-6 * std::max(1.0, hi[j] - lo[j]);
    if (std::find(o.fixed.begin(), o.fixed.end(), j) != o.fixed.end()) continue;
    if (s.x[j] - lo[j] < tol || hi[j] - s.x[j] < tol) s.at_bound.push_back(problem.estimated()[j].id);
  }
  s.usable = std::isfinite(s.final_cost);
  return s;
}

std::string describe(const ResidualProblem& problem, const FitSummary& s) {
  std::ostringstream os;
  os.precision(6);
  os << "fit [" << s.optimizer << "]: " << (s.converged ? "converged" : "NOT converged") << " (" << s.termination
     << ") after " << s.iterations << " iterations, " << s.evaluations << " simulations (" << s.jacobian_evaluations
     << " with sensitivities) in " << s.wall_seconds << " s\n";
  os << "  cost " << s.initial_cost << " -> " << s.final_cost << " (1/2 sum of squared weighted residuals, "
     << problem.num_residuals() << " residuals)\n";
  if (!s.message.empty()) os << "  " << s.message << "\n";
  if (s.failed_evaluations) os << "  " << s.failed_evaluations << " evaluations failed (simulation or feature); treated as rejected steps\n";
  if (!s.at_bound.empty()) {
    os << "  at a bound:";
    for (auto& b : s.at_bound) os << " " << b;
    os << " (the optimum may lie outside the bounds)\n";
  }
  return os.str();
}

}  // namespace phasmid::fit
