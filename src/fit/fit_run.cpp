#include "fit/fit_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <sstream>

#include "common/error.hpp"
#include "parallel/bytes.hpp"
#include "io/h5_file.hpp"

namespace phasmid::fit {

namespace {
// Profiles as tasks, two per profiled parameter (the halves below and above the optimum):
// id 2k + side for the k-th profile; the input carries what only the master knows.
std::vector<parallel::Task> profile_tasks(const std::vector<size_t>& prof, const FitSummary& best, double sigma2,
                                      const std::vector<std::vector<double>>& grids) {
  std::vector<parallel::Task> tasks;
  for (size_t k = 0; k < prof.size(); ++k)
    for (std::uint64_t side : {0, 1})
      tasks.push_back({2 * k + side, parallel::ByteWriter().u64(prof[k]).u64(side).f64s(best.x).f64(best.final_cost)
                                         .f64(sigma2).f64s(grids[k]).take()});
  return tasks;
}

// Runs the profile tasks on `executor` (on every rank; with no tasks it only ends the phase).
std::vector<Profile> run_profiles(const ResidualProblem& problem, const FitSpec& spec, const std::vector<size_t>& prof,
                                  const std::vector<parallel::Task>& tasks, const std::vector<std::vector<double>>& grids,
                                  parallel::Executor& executor) {
  std::vector<Profile> profiles;
  for (size_t k = 0; k < grids.size(); ++k) profiles.push_back(empty_profile(problem, prof[k], grids[k].size()));
  const parallel::Evaluate evaluate = [&](const parallel::Task& t, int) {
    parallel::ByteReader in(t.input);
    const size_t j = in.u64();
    const int dir = in.u64() ? +1 : -1;
    const std::vector<double> x_opt = in.f64s();
    const double cost_opt = in.f64(), sigma2 = in.f64();
    const std::vector<double> grid = in.f64s();
    Profile pr = empty_profile(problem, j, grid.size());
    profile_walk(problem, x_opt, cost_opt, j, sigma2, grid, dir, spec.optimizer, pr);
    std::vector<double> conv(pr.converged.begin(), pr.converged.end());
    return parallel::ByteWriter().f64s(pr.values).f64s(pr.cost).f64s(pr.delta_chi2).f64s(conv).take();
  };
  const parallel::Collect collect = [&](std::size_t id, std::string bytes) {
    Profile& pr = profiles.at(id / 2);
    parallel::ByteReader in(bytes);
    const auto values = in.f64s(), cost = in.f64s(), delta = in.f64s(), conv = in.f64s();
    for (size_t i : profile_side(id % 2 ? +1 : -1, pr.values.size())) {
      pr.values[i] = values.at(i);
      pr.cost[i] = cost.at(i);
      pr.delta_chi2[i] = delta.at(i);
      pr.converged[i] = static_cast<int>(conv.at(i));
    }
  };
  executor.run(tasks, evaluate, collect, [] { return true; });
  return profiles;
}
}  // namespace

FitResult run_fit(const ResidualProblem& problem, const FitSpec& spec) {
  std::vector<size_t> prof;
  for (auto& name : spec.profile) {
    auto names = problem.parameter_names();
    auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) throw Error("profile: '" + name + "' is not an estimated parameter of this fit");
    prof.push_back(static_cast<size_t>(it - names.begin()));
  }
  check_optimizer(problem, spec.optimizer);
  if (!prof.empty() && !problem.has_jacobian())
    throw Error("profile: profile likelihoods re-optimise with Ceres, which needs Jacobians (" +
                problem.no_jacobian_reason() + ")");
  FitResult res;
  auto executor = parallel::make_executor(spec.multistart.threads);
  res.multistart = multistart(problem, spec.optimizer, spec.multistart, *executor);
  if (!executor->is_master()) {  // an MPI worker: serve the profile phase too, report nothing
    run_profiles(problem, spec, {}, {}, {}, *executor);
    res.worker = true;
    return res;
  }
  std::vector<parallel::Task> tasks;
  std::vector<std::vector<double>> grids;
  const FitSummary& b = res.best();
  try {
    res.estimate = problem.to_linear(b.x);
    if (b.usable) {
      res.uncertainty = estimate_uncertainty(problem, b.x, spec.absolute_sigma);
      for (size_t j : prof)
        grids.push_back(profile_grid(problem, b.x, j, res.uncertainty.standard_error_scaled, spec.profile_points,
                                     spec.profile_span));
      tasks = profile_tasks(prof, b, res.uncertainty.sigma2, grids);
    } else {
      res.uncertainty.message = "no usable optimum: no standard errors";
      const size_t n = problem.num_parameters();
      res.uncertainty.standard_error = Eigen::VectorXd::Constant(n, NAN);
      res.uncertainty.standard_error_scaled = Eigen::VectorXd::Constant(n, NAN);
      res.uncertainty.correlation = Eigen::MatrixXd::Constant(n, n, NAN);
    }
  } catch (...) {
    parallel::release_workers();
    throw;
  }
  res.profiles = run_profiles(problem, spec, prof, tasks, grids, *executor);
  return res;
}

std::string format_result(const ResidualProblem& problem, const FitResult& r) {
  std::ostringstream os;
  const FitSummary& b = r.best();
  if (r.multistart.runs.size() > 1) {
    size_t conv = 0;
    for (auto& s : r.multistart.runs) conv += s.converged;
    os << "multistart: " << r.multistart.runs.size() << " starts, " << conv << " converged, best is start "
       << r.multistart.best << "\n";
  }
  os << describe(problem, b);
  size_t w = 9;
  for (auto& p : problem.estimated()) w = std::max(w, p.id.size());
  char line[512];
  std::snprintf(line, sizeof line, "  %-*s  %13s  %11s  %13s  %s\n", static_cast<int>(w), "parameter", "estimate", "std.error",
                "start", "unit");
  os << line;
  for (size_t j = 0; j < problem.num_parameters(); ++j) {
    const auto& p = problem.estimated()[j];
    std::string unit = problem.parameter_unit(j);
    double se = r.uncertainty.standard_error.size() ? r.uncertainty.standard_error[j] : NAN;
    std::snprintf(line, sizeof line, "  %-*s  %13.6g  %11.3g  %13.6g  %s\n", static_cast<int>(w), p.id.c_str(),
                  r.estimate[j], se, from_scaled(p.scale, b.x_start[j]), unit.c_str());
    os << line;
  }
  if (!r.uncertainty.message.empty()) os << "  note: " << r.uncertainty.message << "\n";
  return os.str();
}

namespace {
const char* kParameterUnits = "see /fit/parameter_units";

// /fit: estimates, standard errors, bounds, correlation, residuals.
void write_estimates(io::H5Writer& out, const ResidualProblem& problem, const FitResult& r) {
  const FitSummary& b = r.best();
  const size_t n = problem.num_parameters();
  std::vector<std::string> names = problem.parameter_names(), units, scales;
  std::vector<double> lo, hi, nominal;
  for (size_t j = 0; j < n; ++j) {
    const auto& p = problem.estimated()[j];
    units.push_back(problem.parameter_unit(j));
    scales.push_back(scale_name(p.scale));
    lo.push_back(p.lower);
    hi.push_back(p.upper);
    nominal.push_back(p.nominal);
  }
  const std::string pu = kParameterUnits;
  out.ensure_group("/fit");
  out.write("/fit/parameter_names", names);
  out.write("/fit/parameter_units", units);
  out.write("/fit/parameter_scale", scales);
  for (size_t j = 0; j < n; ++j) {
    auto tied = problem.tied_parameters(j);
    if (tied.size() > 1) out.write("/fit/tied/" + names[j], tied);
  }
  out.write("/fit/estimate", r.estimate, pu);
  std::vector<double> se(n, NAN), se_s(n, NAN), start = problem.to_linear(b.x_start);
  for (size_t j = 0; j < n; ++j) {
    if (r.uncertainty.standard_error.size() == static_cast<long>(n)) se[j] = r.uncertainty.standard_error[j];
    if (r.uncertainty.standard_error_scaled.size() == static_cast<long>(n)) se_s[j] = r.uncertainty.standard_error_scaled[j];
  }
  out.write("/fit/standard_error", se, pu);
  out.write("/fit/standard_error_scaled", se_s, "scaled parameter units (see /fit/parameter_scale)");
  out.write("/fit/start", start, pu);
  out.write("/fit/nominal", nominal, pu);
  out.write("/fit/lower_bound", lo, pu);
  out.write("/fit/upper_bound", hi, pu);
  out.write("/fit/cost_history", b.cost_history.empty() ? std::vector<double>{b.final_cost} : b.cost_history, "1");
  std::vector<double> corr(n * n, NAN);
  if (r.uncertainty.correlation.rows() == static_cast<long>(n))
    for (size_t a = 0; a < n; ++a)
      for (size_t c = 0; c < n; ++c) corr[a * n + c] = r.uncertainty.correlation(a, c);
  out.write("/fit/correlation", corr, "1", {n, n});
  if (r.uncertainty.residuals.size()) {
    std::vector<double> res(r.uncertainty.residuals.data(), r.uncertainty.residuals.data() + r.uncertainty.residuals.size());
    out.write("/fit/residuals", res, "1 (weighted: (model - target) / tolerance)");
  }
  out.write("/fit/residual_labels", problem.residual_labels());
}

// /fit: costs and the optimiser's account (attributes, report, summary).
void write_fit_summary(io::H5Writer& out, const ResidualProblem& problem, const FitSpec& spec, const FitResult& r) {
  const FitSummary& b = r.best();
  // Summary.
  out.write_scalar("/fit/final_cost", b.final_cost, "1");
  out.write_scalar("/fit/initial_cost", b.initial_cost, "1");
  out.write_scalar("/fit/sigma2", r.uncertainty.sigma2, "1");
  out.set_attribute("/fit", "optimizer", b.optimizer);
  out.set_attribute("/fit", "termination", b.termination);
  out.set_attribute("/fit", "message", b.message);
  out.set_attribute("/fit", "converged", b.converged ? 1.0 : 0.0);
  out.set_attribute("/fit", "iterations", static_cast<double>(b.iterations));
  out.set_attribute("/fit", "evaluations", static_cast<double>(b.evaluations));
  out.set_attribute("/fit", "wall_seconds", b.wall_seconds);
  out.set_attribute("/fit", "target_set", spec.target_set);
  out.set_attribute("/fit", "absolute_sigma", spec.absolute_sigma ? 1.0 : 0.0);
  std::string at_bound;
  for (auto& a : b.at_bound) at_bound += (at_bound.empty() ? "" : " ") + a;
  out.set_attribute("/fit", "at_bound", at_bound);
  out.set_attribute("/fit", "uncertainty_note", r.uncertainty.message);
  std::string inputs;
  for (auto& i : spec.inputs) inputs += (inputs.empty() ? "" : " ") + i;
  out.set_attribute("/fit", "inputs", inputs);
  out.write_string("/fit/report", b.report);
  out.write_string("/fit/summary", format_result(problem, r));

}

// /fit/multistart: every start and its optimum, for the waterfall plot.
void write_multistart(io::H5Writer& out, const ResidualProblem& problem, const FitSpec& spec, const FitResult& r) {
  const FitSummary& b = r.best();
  const size_t n = problem.num_parameters();
  const std::string pu = kParameterUnits;
  // Multistart (waterfall).
  const size_t N = r.multistart.runs.size();
  std::vector<double> sp, ep, fc(N), ic(N);
  std::vector<std::int64_t> conv(N), order(N);
  for (size_t i = 0; i < N; ++i) {
    const auto& s = r.multistart.runs[i];
    auto a = problem.to_linear(s.x_start.size() == n ? s.x_start : b.x_start);
    auto e = problem.to_linear(s.x.size() == n ? s.x : b.x_start);
    sp.insert(sp.end(), a.begin(), a.end());
    ep.insert(ep.end(), e.begin(), e.end());
    fc[i] = s.usable ? s.final_cost : NAN;
    ic[i] = s.initial_cost;
    conv[i] = s.converged;
  }
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::int64_t a, std::int64_t c) {
    if (std::isnan(fc[a])) return false;
    if (std::isnan(fc[c])) return true;
    return fc[a] < fc[c];
  });
  out.write("/fit/multistart/start_points", sp, pu, {N, n});
  out.write("/fit/multistart/estimates", ep, pu, {N, n});
  out.write("/fit/multistart/final_cost", fc, "1");
  out.write("/fit/multistart/initial_cost", ic, "1");
  out.write("/fit/multistart/converged", conv, "1");
  out.write("/fit/multistart/waterfall_order", order, "1");
  out.set_attribute("/fit/multistart", "best", static_cast<double>(r.multistart.best));
  out.set_attribute("/fit/multistart", "sampling", spec.multistart.sampling == Sampling::Sobol ? std::string("sobol") : std::string("lhs"));
  out.set_attribute("/fit/multistart", "seed", static_cast<double>(spec.multistart.seed));

}

// /fit/targets and /fit/profile/<parameter>.
void write_targets_and_profiles(io::H5Writer& out, const ResidualProblem& problem, const FitSpec& spec,
                                const FitResult& r) {
  // Targets at the optimum.
  if (!spec.targets.features.empty()) {
    std::vector<std::string> fn;
    std::vector<double> tv, tol;
    for (auto& f : spec.targets.features) {
      fn.push_back(f.feature);
      tv.push_back(f.value);
      tol.push_back(f.tolerance);
    }
    out.write("/fit/targets/feature_names", fn);
    out.write("/fit/targets/feature_values", tv, "feature units");
    out.write("/fit/targets/feature_tolerances", tol, "feature units");
  }

  // Profiles.
  for (auto& p : r.profiles) {
    const std::string g = "/fit/profile/" + p.parameter;
    auto names_ = problem.parameter_names();
    size_t jp = static_cast<size_t>(std::find(names_.begin(), names_.end(), p.parameter) - names_.begin());
    out.write(g + "/values", p.values, problem.parameter_unit(jp));
    out.write(g + "/cost", p.cost, "1");
    out.write(g + "/delta_chi2", p.delta_chi2, "1");
    std::vector<std::int64_t> c(p.converged.begin(), p.converged.end());
    out.write(g + "/converged", c, "1");
    out.set_attribute(g, "threshold_95", 3.841458820694124);
  }

}
}  // namespace

void write_fit_h5(io::H5Writer& out, const ResidualProblem& problem, const FitSpec& spec, const FitResult& r) {
  const FitSummary& b = r.best();
  write_estimates(out, problem, r);
  write_fit_summary(out, problem, spec, r);
  write_multistart(out, problem, spec, r);
  write_targets_and_profiles(out, problem, spec, r);

  // The model at the optimum (or the start when there is none).
  try {
    problem.write_model_output(out, b.usable ? b.x.data() : b.x_start.data(), b.usable, spec.output_dt_ms);
    if (!b.usable)
      out.set_attribute("/fit", "trajectory_note", std::string("no usable optimum: no best-fit trajectory; /parameters holds the start"));
  } catch (const Error& e) {
    out.set_attribute("/fit", "trajectory_note", std::string("best-fit trajectory not written: ") + e.what());
  }
}

}  // namespace phasmid::fit
