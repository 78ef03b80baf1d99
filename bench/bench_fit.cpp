// A fit with exact Jacobians from forward sensitivities, next to the same fit with Ceres'
// central finite-difference Jacobian, in the same run (docs/performance.md, "Fits").
//   build/bench/bench_fit [repeats] [CONFIG [DATA]]
// Default: the FTi kinematic fit (five mechanical parameters of Section 3.1 from the synthetic
// recording in datasets/synthetic/); target: the whole fit <= 0.5 s; goal <= 0.13 s. DATA
// replaces the config's recording (phasmid fit --data), e.g. the recording fit
// configs/fit_recording_middle_leg.toml on a Stick Insect Locomotion trial.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "config/config.hpp"
#include "config/fit_section.hpp"
#include "fit/fit_problem.hpp"
#include "scenario/scenario.hpp"
#include "fit/optimizer.hpp"
#include "build_info.hpp"

using namespace phasmid;

namespace {
struct Timing {
  double median_s, min_s;
  fit::FitSummary last;
};

Timing time_fit(const fit::ResidualProblem& p, const fit::OptimizerOptions& o, int repeats) {
  std::vector<double> t;
  Timing r{};
  for (int i = 0; i < repeats; ++i) {
    auto t0 = std::chrono::steady_clock::now();
    r.last = fit::optimize(p, p.start(), o);
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  r.median_s = t[t.size() / 2];
  r.min_s = t.front();
  return r;
}

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }
}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const std::string config_path =
      argc > 2 ? argv[2] : std::string(PHASMID_SOURCE_DIR) + "/configs/fit_fti_kinematic_synthetic.toml";
  const bool shipped = argc <= 2;
  fit::FitOverrides overrides;
  if (argc > 3) overrides.data = argv[3];
  auto cfg = config::load_config(config_path);
  auto scenario = config::build_scenario(cfg, {});
  fit::FitSpec spec = config::fit_spec(cfg, *scenario, overrides);
  if (std::getenv("BENCH_SIMULT")) spec.problem.solver.sensitivity_method = solver::SensitivityMethod::Simultaneous;
  if (std::getenv("BENCH_NOERRCON")) spec.problem.solver.sensitivity_error_control = false;
  if (std::getenv("BENCH_RTOL")) spec.problem.solver.rtol = spec.problem.solver.atol = std::atof(std::getenv("BENCH_RTOL"));
  const auto made = scenario->make_fit(spec);  // with [fit.conditions], one problem per trial
  const fit::ResidualProblem& problem = *made;

  // One simulation with and without sensitivities, for scale.
  std::vector<double> x = problem.start(), r(problem.num_residuals()), J(problem.num_residuals() * problem.num_parameters());
  auto t0 = std::chrono::steady_clock::now();
  const int evals = shipped ? 20 : 1;
  for (int i = 0; i < evals; ++i) problem.evaluate(x.data(), r.data(), nullptr);
  double t_res = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / evals;
  t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < evals; ++i) problem.evaluate(x.data(), r.data(), J.data());
  double t_jac = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / evals;

  fit::OptimizerOptions exact = spec.optimizer, fd = spec.optimizer;
  fd.numeric_jacobian = true;
  double c0 = cpu_seconds();
  Timing te = time_fit(problem, exact, repeats);
  double cpu_exact = (cpu_seconds() - c0) / repeats;
  c0 = cpu_seconds();
  Timing tf = time_fit(problem, fd, repeats);
  double cpu_fd = (cpu_seconds() - c0) / repeats;

  std::printf("bench_fit: %zu parameters, %zu residuals (%s%s%s), %d repeats\n", problem.num_parameters(),
              problem.num_residuals(), config_path.c_str(), overrides.data.empty() ? "" : ", data ",
              overrides.data.c_str(), repeats);
  std::printf("  one evaluation: residuals %.2f ms, residuals + Jacobian (forward sensitivities) %.2f ms\n", t_res * 1e3,
              t_jac * 1e3);
  std::printf("  %-34s %9s %9s %9s %6s %8s %12s\n", "fit", "median s", "min s", "cpu s", "iter", "sims", "final cost");
  std::printf("  %-34s %9.3f %9.3f %9.3f %6d %8ld %12.6g\n", "Ceres, exact Jacobian (sensitivity)", te.median_s, te.min_s,
              cpu_exact, te.last.iterations, te.last.evaluations, te.last.final_cost);
  std::printf("  %-34s %9.3f %9.3f %9.3f %6d %8ld %12.6g\n", "Ceres, central finite differences", tf.median_s, tf.min_s,
              cpu_fd, tf.last.iterations, tf.last.evaluations, tf.last.final_cost);
  std::printf("  exact: %s\n  finite differences: %s\n", te.last.message.c_str(), tf.last.message.c_str());
  std::printf("  ratio finite-difference / exact: %.2f (median wall), %.2f (cpu)\n", tf.median_s / te.median_s,
              cpu_fd / cpu_exact);
  if (shipped)
    std::printf("  target <= 0.5 s: %s; goal <= 0.13 s: %s\n", te.median_s <= 0.5 ? "met" : "NOT met",
                te.median_s <= 0.13 ? "met" : "not met");
  return 0;
}
