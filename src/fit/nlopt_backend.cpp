// NLopt back end (C API): minimises cost = 1/2 sum r^2; gradient-based algorithms get the
// exact gradient J^T r from the same forward sensitivities as Ceres.
#include <nlopt.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "common/error.hpp"
#include "fit/optimizer.hpp"

namespace phasmid::fit {
namespace {

struct Data {
  const ResidualProblem* problem;
  const OptimizerOptions* options;
  std::vector<double> r, J;
  std::vector<double>* history;
  double best = std::numeric_limits<double>::infinity();
  double first = std::numeric_limits<double>::quiet_NaN();
  double penalty = 0;
  long evals = 0, jac_evals = 0, failed = 0;
  std::string last_error;
  bool tty = false;
  std::chrono::steady_clock::time_point last_print;
  nlopt_opt opt = nullptr;
};

double objective(unsigned n, const double* x, double* grad, void* ud) {
  auto* d = static_cast<Data*>(ud);
  const size_t m = d->problem->num_residuals();
  ++d->evals;
  if (grad) ++d->jac_evals;
  bool ok = d->problem->evaluate(x, d->r.data(), grad ? d->J.data() : nullptr, &d->last_error);
  if (!ok) {
    ++d->failed;
    if (grad) {
      // A gradient method cannot step around a hole: stop and report.
      nlopt_force_stop(d->opt);
      return HUGE_VAL;
    }
    // Derivative-free and global methods: a large finite penalty steers them away.
    return d->penalty > 0 ? d->penalty : 1e100;
  }
  double c = 0;
  for (size_t q = 0; q < m; ++q) c += 0.5 * d->r[q] * d->r[q];
  if (grad)
    for (unsigned j = 0; j < n; ++j) {
      double g = 0;
      for (size_t q = 0; q < m; ++q) g += d->J[q * n + j] * d->r[q];
      grad[j] = g;
    }
  if (std::isnan(d->first)) {
    d->first = c;
    d->penalty = 1e6 * (1 + c);
  }
  if (c < d->best) {
    d->best = c;
    d->history->push_back(c);
  }
  if (d->tty) {
    auto now = std::chrono::steady_clock::now();
    if (now - d->last_print > std::chrono::milliseconds(150)) {
      std::fprintf(stderr, "\r%s [%s] evaluation %4ld  best cost %.6g   ", d->options->progress_label.c_str(),
                   d->options->method.c_str(), d->evals, d->best);
      d->last_print = now;
    }
  }
  return c;
}

const char* result_name(nlopt_result r) {
  switch (r) {
    case NLOPT_SUCCESS: return "SUCCESS";
    case NLOPT_STOPVAL_REACHED: return "STOPVAL_REACHED";
    case NLOPT_FTOL_REACHED: return "FTOL_REACHED";
    case NLOPT_XTOL_REACHED: return "XTOL_REACHED";
    case NLOPT_MAXEVAL_REACHED: return "MAXEVAL_REACHED";
    case NLOPT_MAXTIME_REACHED: return "MAXTIME_REACHED";
    case NLOPT_FAILURE: return "FAILURE";
    case NLOPT_INVALID_ARGS: return "INVALID_ARGS";
    case NLOPT_OUT_OF_MEMORY: return "OUT_OF_MEMORY";
    case NLOPT_ROUNDOFF_LIMITED: return "ROUNDOFF_LIMITED";
    case NLOPT_FORCED_STOP: return "FORCED_STOP";
    default: return "UNKNOWN";
  }
}

struct OptHandle {
  nlopt_opt o = nullptr;
  ~OptHandle() {
    if (o) nlopt_destroy(o);
  }
};
}  // namespace

FitSummary optimize_nlopt(const ResidualProblem& problem, const std::vector<double>& x0, const OptimizerOptions& o) {
  FitSummary out;
  if (!o.fixed.empty()) throw Error("internal: fixed parameters are supported by the Ceres back end only");
  const unsigned n = static_cast<unsigned>(problem.num_parameters());
  const OptimizerInfo& info = optimizer_info(o);
  if (info.backend != Backend::NLopt) throw Error("internal: " + info.name + " is not an NLopt optimizer");
  const std::string algo = info.name.substr(info.name.find(':') + 1);  // "BOBYQA" of "nlopt:BOBYQA"
  OptHandle h, local;
  h.o = nlopt_create(static_cast<nlopt_algorithm>(info.nlopt_algorithm), n);
  if (!h.o) throw Error("NLopt could not create " + algo + " for " + std::to_string(n) + " parameters");
  std::vector<double> lo = problem.lower(), hi = problem.upper(), x = x0;
  for (unsigned j = 0; j < n; ++j) x[j] = std::min(std::max(x[j], lo[j]), hi[j]);
  nlopt_set_lower_bounds(h.o, lo.data());
  nlopt_set_upper_bounds(h.o, hi.data());
  Data d;
  d.problem = &problem;
  d.options = &o;
  d.r.resize(problem.num_residuals());
  d.J.resize(problem.num_residuals() * n);
  d.history = &out.cost_history;
  d.tty = o.progress && isatty(STDERR_FILENO);
  d.opt = h.o;
  nlopt_set_min_objective(h.o, objective, &d);
  nlopt_set_ftol_rel(h.o, o.function_tolerance);
  nlopt_set_xtol_rel(h.o, o.parameter_tolerance);
  nlopt_set_maxeval(h.o, o.max_evaluations);
  if (!info.local.empty()) {
    local.o = nlopt_create(static_cast<nlopt_algorithm>(find_optimizer(info.local).nlopt_algorithm), n);
    nlopt_set_ftol_rel(local.o, 1e-8);
    nlopt_set_xtol_rel(local.o, 1e-8);
    nlopt_set_maxeval(local.o, std::max(20, o.max_evaluations / 10));
    nlopt_set_local_optimizer(h.o, local.o);
  }
  if (info.seeded) nlopt_srand(12345);
  // Initial step for local derivative-free methods: a tenth of the (scaled) range.
  if (!info.needs_gradient && !info.global) {
    std::vector<double> dx(n);
    for (unsigned j = 0; j < n; ++j) dx[j] = 0.1 * (hi[j] - lo[j]);
    nlopt_set_initial_step(h.o, dx.data());
  }
  double f = NAN;
  nlopt_result res = nlopt_optimize(h.o, x.data(), &f);
  if (d.tty) std::fprintf(stderr, "\n");
  out.x = x;
  out.termination = result_name(res);
  out.converged = res == NLOPT_SUCCESS || res == NLOPT_STOPVAL_REACHED || res == NLOPT_FTOL_REACHED ||
                  res == NLOPT_XTOL_REACHED;
  if (info.global && res == NLOPT_MAXEVAL_REACHED) {
    out.converged = true;  // global methods have no local convergence test; the budget is the stop rule
    out.message = "global search used its evaluation budget (" + std::to_string(o.max_evaluations) + ")";
  }
  if (res == NLOPT_FORCED_STOP) out.message = "stopped: an evaluation failed (" + d.last_error + ")";
  else if (d.failed) out.message += (out.message.empty() ? "" : "; ") + std::string("last failed evaluation: ") + d.last_error;
  out.initial_cost = d.first;
  out.final_cost = std::isfinite(d.best) ? d.best : NAN;
  if (res < 0 && res != NLOPT_FORCED_STOP && res != NLOPT_ROUNDOFF_LIMITED) out.converged = false;
  if (res == NLOPT_ROUNDOFF_LIMITED) out.converged = true;  // as good as the arithmetic allows
  out.iterations = static_cast<int>(d.evals);
  out.evaluations = d.evals;
  out.jacobian_evaluations = d.jac_evals;
  out.failed_evaluations = d.failed;
  out.report = "nlopt " + algo + ": " + result_name(res) + ", " + std::to_string(d.evals) + " evaluations";
  return out;
}

}  // namespace phasmid::fit
