#include "fit/optimizer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include <nlopt.h>

#include "common/error.hpp"

namespace phasmid::fit {

namespace {
std::string upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::toupper(c); });
  return s;
}

// "NLOPT:LN_BOBYQA" -> "NLOPT:BOBYQA": NLopt's family prefixes are accepted and ignored.
std::string without_nlopt_family(const std::string& spec) {
  const std::string pre = "NLOPT:";
  if (spec.rfind(pre, 0) != 0) return spec;
  std::string name = spec.substr(pre.size());
  for (const std::string family : {"LN_", "LD_", "GN_", "GD_", "G_"})
    if (name.rfind(family, 0) == 0) return pre + name.substr(family.size());
  return spec;
}

std::string kind(const OptimizerInfo& a) {
  std::string k = std::string(a.global ? "global" : "local") + ", " + (a.needs_gradient ? "gradient" : "derivative-free");
  if (a.robust_loss) k += ", robust losses";
  if (!a.local.empty()) k += ", local searches " + a.local;
  return k;
}
}  // namespace

const std::vector<OptimizerInfo>& optimizers() {
  using B = Backend;
  // name, backend, NLopt algorithm, needs_gradient, global, seeded, robust_loss, local, aliases, description
  static const std::vector<OptimizerInfo> table = {
      {"ceres", B::Ceres, -1, true, false, false, true, "", {}, "Levenberg-Marquardt trust region, dense QR"},
      {"nlopt:BOBYQA", B::NLopt, NLOPT_LN_BOBYQA, false, false, false, false, "", {"nlopt"},
       "quadratic models in a trust region"},
      {"nlopt:COBYLA", B::NLopt, NLOPT_LN_COBYLA, false, false, false, false, "", {}, "linear models in a trust region"},
      {"nlopt:NELDERMEAD", B::NLopt, NLOPT_LN_NELDERMEAD, false, false, false, false, "", {"nlopt:NELDER_MEAD"},
       "Nelder-Mead simplex"},
      {"nlopt:SBPLX", B::NLopt, NLOPT_LN_SBPLX, false, false, false, false, "", {}, "Nelder-Mead on subspaces"},
      {"nlopt:LBFGS", B::NLopt, NLOPT_LD_LBFGS, true, false, false, false, "", {}, "limited-memory BFGS"},
      {"nlopt:SLSQP", B::NLopt, NLOPT_LD_SLSQP, true, false, false, false, "", {}, "sequential quadratic programming"},
      {"nlopt:MMA", B::NLopt, NLOPT_LD_MMA, true, false, false, false, "", {}, "method of moving asymptotes"},
      {"nlopt:DIRECT_L", B::NLopt, NLOPT_GN_DIRECT_L, false, true, false, false, "", {"nlopt:DIRECT-L", "nlopt:DIRECTL"},
       "locally biased dividing rectangles"},
      {"nlopt:CRS2_LM", B::NLopt, NLOPT_GN_CRS2_LM, false, true, true, false, "", {"nlopt:CRS2", "nlopt:CRS"},
       "controlled random search with local mutation"},
      {"nlopt:ISRES", B::NLopt, NLOPT_GN_ISRES, false, true, true, false, "", {}, "improved stochastic ranking evolution strategy"},
      {"nlopt:MLSL", B::NLopt, NLOPT_G_MLSL_LDS, true, true, true, false, "nlopt:LBFGS", {"nlopt:MLSL_LDS"},
       "multi-level single linkage from low-discrepancy starts"},
  };
  return table;
}

std::string optimizer_list(bool (*keep)(const OptimizerInfo&)) {
  std::string list;
  for (const auto& a : optimizers())
    if (!keep || keep(a)) list += (list.empty() ? "" : ", ") + a.name;
  return list;
}

const OptimizerInfo& find_optimizer(const std::string& spec) {
  const std::string s = without_nlopt_family(upper(spec));
  for (const auto& a : optimizers()) {
    if (upper(a.name) == s) return a;
    for (const auto& alias : a.aliases)
      if (upper(alias) == s) return a;
  }
  throw Error("unknown optimizer '" + spec + "' (expected one of " + optimizer_list() + ")");
}

std::string optimizer_help() {
  size_t width = 0;
  for (const auto& a : optimizers()) width = std::max(width, a.name.size());
  std::string help = "one of (default " + optimizers().front().name + "):";
  for (const auto& a : optimizers())
    help += "\n  " + a.name + std::string(width + 2 - a.name.size(), ' ') + kind(a) + ": " + a.description;
  return help;
}

void parse_optimizer(const std::string& spec, OptimizerOptions& o) { o.method = find_optimizer(spec).name; }

const OptimizerInfo& optimizer_info(const OptimizerOptions& o) {
  for (const auto& a : optimizers())
    if (a.name == o.method) return a;
  throw Error("internal: optimizer '" + o.method + "' is not in the table (expected one of " + optimizer_list() + ")");
}

bool needs_jacobian(const OptimizerOptions& o) { return optimizer_info(o).needs_gradient; }

void check_optimizer(const ResidualProblem& problem, const OptimizerOptions& o) {
  if (problem.has_jacobian() || !needs_jacobian(o)) return;
  throw Error("optimizer " + o.method + " needs a gradient but the model has none: " + problem.no_jacobian_reason() +
              "; use one of " +
              optimizer_list([](const OptimizerInfo& a) { return !a.needs_gradient; }));
}

FitSummary optimize(const ResidualProblem& problem, const std::vector<double>& x0, const OptimizerOptions& o) {
  check_optimizer(problem, o);
  if (x0.size() != problem.num_parameters()) throw Error("internal: start vector has the wrong size");
  auto t0 = std::chrono::steady_clock::now();
  const bool ceres = optimizer_info(o).backend == Backend::Ceres;
  FitSummary s = ceres ? optimize_ceres(problem, x0, o) : optimize_nlopt(problem, x0, o);
  s.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  s.optimizer = o.method;
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
