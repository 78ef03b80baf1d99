// Wall time of walking simulations next to the dissertation's compute times (Knops 2013,
// Section 2.6: 2 s for one joint, 15 s for one leg, 180 s for three legs, each for 9 s of
// walking). Usage:
//   bench_walking [T_END_MS=9000] [models=joint,leg,three] [dense|band|klu|auto]
//                 [motoneurons=spiking,rate] [RTOL=1e-6] [integration=parts[,neurons][,whole]]
// Prints one line per model and motoneuron formulation (Hodgkin-Huxley "spiking" MNs or the
// "rate" formulation, docs/model.md): states, simulated ms, wall s, steps, RHS and Jacobian
// evaluations, the ratio to the 2013 time scaled to the simulated duration, and gait features
// to compare formulations and tolerances (after T_END/2, at most 2500 ms, is discarded): the
// period (the FTi joint's; the middle leg's step period for leg and three legs), for the
// three legs the lags hind->middle and middle->front (in periods). `integration=parts,whole` adds a row per model
// integrated as one system ("[whole]", Partitioning::Off; "parts" forces On), the baseline of
// the partitioned integration (solver/partitioned_simulator.hpp; the single joint is one part
// either way; "neurons": Partitioning::Neurons, the spiking cells apart from their networks,
// "[neurons]"). Times are the best of BENCH_REPEATS (default 3) runs.
// Environment: BENCH_INTEGRATOR=name selects the integrator ([simulation] integrator names:
// cvodes_bdf, dopri5), BENCH_THREADS, BENCH_WINDOW_MS the partitioned run's threads and window
// (SolverOptions::threads, window_ms),
// BENCH_STIFF_TOL the neurons partition's network parts' tolerance (SolverOptions::stiff_part_tol),
// BENCH_ATOL_UNITS="1=1e-6,mV=1e-5" the absolute tolerances by unit
// (SolverOptions::atol_by_unit). CPU s is the process's, all threads.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include "features/features.hpp"
#include "solver/integrator_kind.hpp"
#include "solver/simulator.hpp"
#include "walking_models.hpp"

using namespace phasmid;

int main(int argc, char** argv) {
  const double t_end = argc > 1 ? std::atof(argv[1]) : 9000.0;
  const std::string which = argc > 2 ? argv[2] : "joint,leg,three";
  const std::string ls = argc > 3 ? argv[3] : "auto";
  const std::string formulations = argc > 4 ? argv[4] : "spiking,rate";
  const std::string integrations = argc > 6 ? argv[6] : "parts";
  const int repeats = std::getenv("BENCH_REPEATS") ? std::max(1, std::atoi(std::getenv("BENCH_REPEATS"))) : 3;
  solver::SolverOptions so;
  so.rtol = so.atol = argc > 5 ? std::atof(argv[5]) : 1e-6;  // default: the three-leg configs' tolerance
  if (const char* e = std::getenv("BENCH_THREADS")) so.threads = std::atoi(e);
  if (const char* e = std::getenv("BENCH_STIFF_TOL")) so.stiff_part_tol = std::atof(e);
  if (const char* e = std::getenv("BENCH_WINDOW_MS")) so.window_ms = std::atof(e);
  if (const char* e = std::getenv("BENCH_ATOL_UNITS")) {  // "1=1e-5,mV=1e-4"
    for (std::string item, rest = e; !rest.empty();) {
      const size_t comma = rest.find(',');
      item = rest.substr(0, comma);
      rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
      const size_t eq = item.find('=');
      if (eq != std::string::npos) so.atol_by_unit.emplace_back(item.substr(0, eq), std::atof(item.c_str() + eq + 1));
    }
  }
  if (const char* e = std::getenv("BENCH_INTEGRATOR")) {
    const auto kind = solver::integrator_from_name(e);
    if (!kind) {
      std::fprintf(stderr, "bench_walking: BENCH_INTEGRATOR must be one of %s\n", solver::integrator_names().c_str());
      return 2;
    }
    so.integrator = *kind;
  }
  if (ls == "dense") so.linear_solver = solver::LinearSolverKind::Dense;
  if (ls == "band") so.linear_solver = solver::LinearSolverKind::Band;
  if (ls == "klu") so.linear_solver = solver::LinearSolverKind::Klu;
  struct Case {
    const char* key;
    const char* label;
    double t2013_s;  // for 9 s of walking
  };
  const Case cases[] = {{"joint", "single joint (FTi)", 2.0}, {"leg", "middle leg", 15.0}, {"three", "three legs (tetrapod)", 180.0}};
  std::printf("# bench_walking: %.0f ms simulated, rtol = atol = %g, %s linear solver, best of %d runs\n", t_end, so.rtol,
              ls.c_str(), repeats);
  std::printf("%-38s %7s %8s %8s %8s %8s %9s %7s %14s %8s %8s %7s %7s\n", "model", "states", "sim_ms", "wall_s", "cpu_s", "steps",
              "rhs", "jac", "2013_s(scaled)", "ratio",
              "period", "lag_hm", "lag_mf");
  for (const Case& c : cases) {
    if (which.find(c.key) == std::string::npos) continue;
    for (const char* form : {"spiking", "rate"})
    for (const char* integ : {"parts", "neurons", "whole"}) {
      if (formulations.find(form) == std::string::npos || integrations.find(integ) == std::string::npos) continue;
      const model::MotoneuronModel mn = model::parse_motoneuron_model(form);
      std::unique_ptr<model::NetworkModel> m = bench::build_walking_model(c.key, mn);
      solver::SolverOptions sok = so;
      sok.partitioning = std::string(integ) == "parts"     ? solver::Partitioning::On
                         : std::string(integ) == "neurons" ? solver::Partitioning::Neurons
                                                           : solver::Partitioning::Off;
      solver::Simulator sim(*m, sok);
      // Best of `repeats` runs: single timings on a shared machine scatter (docs/performance.md).
      double wall = 1e300, cpu = 1e300;
      solver::SolveResult r;
      for (int rep = 0; rep < repeats; ++rep) {
        auto t0 = std::chrono::steady_clock::now();
        std::clock_t c0 = std::clock();
        r = sim.run(m->parameters().values(), solver::output_grid(t_end, 5.0), features::feature_roots(*m));
        wall = std::min(wall, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        cpu = std::min(cpu, double(std::clock() - c0) / CLOCKS_PER_SEC);
      }
      double ref = c.t2013_s * t_end / 9000.0;
      features::FeatureOptions fo;
      fo.discard_ms = std::min(2500.0, t_end / 2);
      std::map<std::string, double> f;
      for (auto& x : features::compute_features(*m, r, fo)) f[x.name] = x.value;
      auto get = [&](const char* k) { return f.count(k) ? f[k] : NAN; };
      const std::string label =
          std::string(c.label) + " " + form + (std::string(integ) == "parts" ? "" : " [" + std::string(integ) + "]");
      std::printf("%-38s %7zu %8.0f %8.2f %8.2f %8ld %9ld %7ld %14.1f %8.3f %8.1f %7.3f %7.3f\n", label.c_str(),
                  m->num_states(), t_end, wall, cpu, r.stats.steps, r.stats.rhs_evals, r.stats.jac_evals, ref, wall / ref,
                  f.count("middle.step_period_ms") ? f["middle.step_period_ms"] : get("period_ms"), get("phase_lag.hind_to_middle"), get("phase_lag.middle_to_front"));
      std::fprintf(stderr, "#   %s: error-test failures %ld, Newton iterations %ld (failures %ld), linear-solver setups %ld\n",
                   label.c_str(), r.stats.error_test_failures, r.stats.newton_iterations, r.stats.newton_failures,
                   r.stats.linear_setups);
    }
  }
  return 0;
}
