// Ceres back end: one residual block with the analytic (forward-sensitivity) Jacobian, or,
// with a robust loss, one block per residual sharing a cached evaluation (the loss must act
// on each residual, not on the norm of all of them).
#include <ceres/ceres.h>
#include <glog/logging.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include "common/error.hpp"
#include "fit/optimizer.hpp"

namespace phasmid::fit {
namespace {

struct Shared {
  const ResidualProblem* problem;
  mutable std::string last_error;
  mutable long failed = 0, calls = 0, jacobian_calls = 0;
  bool eval(const double* x, double* r, double* J) const {
    ++calls;
    if (J) ++jacobian_calls;
    bool ok = problem->evaluate(x, r, J, &last_error);
    if (!ok) ++failed;
    return ok;
  }
};

// All residuals with exact Jacobian.
class SensitivityCost : public ceres::CostFunction {
 public:
  explicit SensitivityCost(const Shared& s) : s_(s) {
    set_num_residuals(static_cast<int>(s.problem->num_residuals()));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(s.problem->num_parameters()));
  }
  bool Evaluate(double const* const* x, double* r, double** J) const override {
    return s_.eval(x[0], r, J ? J[0] : nullptr);
  }

 private:
  const Shared& s_;
};

// Residuals only (for the finite-difference baseline).
struct ResidualFunctor {
  const Shared* s;
  bool operator()(double const* const* x, double* r) const {
    return s->eval(x[0], r, nullptr);
  }
};

// One residual of a cached full evaluation (robust losses).
struct Cache {
  const Shared* s;
  std::vector<double> x, r, J;
  bool have_J = false, ok = false;
  bool get(const double* xv, bool need_J) {
    const size_t n = s->problem->num_parameters(), m = s->problem->num_residuals();
    if (x.size() == n && std::memcmp(x.data(), xv, n * sizeof(double)) == 0 && (have_J || !need_J)) return ok;
    x.assign(xv, xv + n);
    r.resize(m);
    J.resize(m * n);
    have_J = need_J;
    ok = s->eval(xv, r.data(), need_J ? J.data() : nullptr);
    return ok;
  }
};
class CachedResidual : public ceres::CostFunction {
 public:
  CachedResidual(Cache& c, size_t row) : c_(c), row_(row) {
    set_num_residuals(1);
    mutable_parameter_block_sizes()->push_back(static_cast<int>(c.s->problem->num_parameters()));
  }
  bool Evaluate(double const* const* x, double* r, double** J) const override {
    if (!c_.get(x[0], J && J[0])) return false;
    const size_t n = c_.s->problem->num_parameters();
    r[0] = c_.r[row_];
    if (J && J[0]) std::copy(c_.J.begin() + row_ * n, c_.J.begin() + (row_ + 1) * n, J[0]);
    return true;
  }

 private:
  Cache& c_;
  size_t row_;
};

ceres::LossFunction* make_loss(const std::string& name, double a) {
  if (name == "none" || name.empty()) return nullptr;
  if (!(a > 0)) throw Error("loss_scale must be > 0");
  if (name == "huber") return new ceres::HuberLoss(a);
  if (name == "cauchy") return new ceres::CauchyLoss(a);
  if (name == "soft_l1") return new ceres::SoftLOneLoss(a);
  if (name == "arctan") return new ceres::ArctanLoss(a);
  throw Error("unknown loss '" + name + "' (expected none, huber, cauchy, soft_l1 or arctan)");
}

class History : public ceres::IterationCallback {
 public:
  History(std::vector<double>& h, const OptimizerOptions& o) : h_(h), o_(o), tty_(o.progress && isatty(STDERR_FILENO)) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& it) override {
    h_.push_back(it.cost);
    if (tty_) std::fprintf(stderr, "\r%s [ceres] iteration %3d  cost %.6g   ", o_.progress_label.c_str(), it.iteration, it.cost);
    return ceres::SOLVER_CONTINUE;
  }
  ~History() override {
    if (tty_) std::fprintf(stderr, "\n");
  }

 private:
  std::vector<double>& h_;
  const OptimizerOptions& o_;
  bool tty_;
};

}  // namespace

FitSummary optimize_ceres(const ResidualProblem& problem, const std::vector<double>& x0, const OptimizerOptions& o) {
  // Ceres logs a failed evaluation through glog even with logging_type = SILENT; phasmid reports
  // failures in the summary instead (the CLI contract is one line on stderr per error).
  static const bool quiet_glog = [] {
    FLAGS_minloglevel = google::GLOG_FATAL;
    return true;
  }();
  (void)quiet_glog;
  FitSummary out;
  Shared shared{&problem, {}};
  const size_t n = problem.num_parameters(), m = problem.num_residuals();
  std::vector<double> x = x0;
  const auto lo = problem.lower(), hi = problem.upper();
  for (size_t j = 0; j < n; ++j) x[j] = std::min(std::max(x[j], lo[j]), hi[j]);

  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  po.loss_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem cp(po);
  Cache cache{&shared, {}, {}, {}, false, false};
  const bool robust = !(o.loss == "none" || o.loss.empty());
  if (o.numeric_jacobian) {
    ceres::NumericDiffOptions nd;
    auto* cf = new ceres::DynamicNumericDiffCostFunction<ResidualFunctor, ceres::CENTRAL>(
        new ResidualFunctor{&shared}, ceres::TAKE_OWNERSHIP, nd);
    cf->AddParameterBlock(static_cast<int>(n));
    cf->SetNumResiduals(static_cast<int>(m));
    cp.AddResidualBlock(cf, make_loss(o.loss, o.loss_scale), x.data());
  } else if (!robust) {
    cp.AddResidualBlock(new SensitivityCost(shared), nullptr, x.data());
  } else {
    for (size_t q = 0; q < m; ++q) cp.AddResidualBlock(new CachedResidual(cache, q), make_loss(o.loss, o.loss_scale), x.data());
  }
  for (size_t j = 0; j < n; ++j) {
    cp.SetParameterLowerBound(x.data(), static_cast<int>(j), lo[j]);
    cp.SetParameterUpperBound(x.data(), static_cast<int>(j), hi[j]);
  }
  if (!o.fixed.empty()) {
    if (o.fixed.size() >= n) {
      cp.SetParameterBlockConstant(x.data());
    } else {
      std::vector<int> fixed(o.fixed.begin(), o.fixed.end());
      cp.SetManifold(x.data(), new ceres::SubsetManifold(static_cast<int>(n), fixed));
    }
  }

  ceres::Solver::Options so;
  so.minimizer_type = ceres::TRUST_REGION;
  so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = o.max_iterations;
  so.function_tolerance = o.function_tolerance;
  so.parameter_tolerance = o.parameter_tolerance;
  so.gradient_tolerance = o.gradient_tolerance;
  so.initial_trust_region_radius = o.initial_trust_region_radius;
  so.max_trust_region_radius = std::max(1e16, o.initial_trust_region_radius);
  so.num_threads = 1;
  so.logging_type = ceres::SILENT;
  so.minimizer_progress_to_stdout = false;
  so.update_state_every_iteration = false;
  History hist(out.cost_history, o);
  so.callbacks.push_back(&hist);
  ceres::Solver::Summary summary;
  if (o.fixed.size() >= n) {
    // Nothing to optimise: evaluate once.
    std::vector<double> r(m);
    double cost = NAN;
    if (problem.evaluate(x.data(), r.data(), nullptr, &shared.last_error)) {
      cost = 0;
      for (double v : r) cost += 0.5 * v * v;
    }
    out.x = x;
    out.initial_cost = out.final_cost = cost;
    out.converged = std::isfinite(cost);
    out.termination = out.converged ? "CONVERGENCE" : "FAILURE";
    out.cost_history = {cost};
    out.evaluations = 1;
    if (!out.converged) out.message = "evaluation failed: " + shared.last_error;
    return out;
  }
  ceres::Solve(so, &cp, &summary);
  out.x = x;
  out.report = summary.FullReport();
  out.termination = ceres::TerminationTypeToString(summary.termination_type);
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  out.message = summary.message;
  if (shared.failed && !shared.last_error.empty()) out.message += (out.message.empty() ? "" : "; ") + std::string("last failed evaluation: ") + shared.last_error;
  out.failed_evaluations = shared.failed;
  out.iterations = std::max(0, static_cast<int>(summary.iterations.size()) - 1);
  out.evaluations = shared.calls;
  out.jacobian_evaluations = shared.jacobian_calls;
  if (summary.termination_type == ceres::FAILURE && summary.iterations.empty()) {
    out.initial_cost = out.final_cost = NAN;
  } else {
    out.initial_cost = summary.initial_cost;
    out.final_cost = summary.final_cost;
  }
  if (summary.termination_type == ceres::FAILURE && !std::isfinite(summary.initial_cost)) out.final_cost = NAN;
  return out;
}

}  // namespace phasmid::fit
