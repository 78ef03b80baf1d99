// The linear solver of CVODES BDF for the walking models as one system, measured in one run:
// dense LU and KLU (sparse), both with the AD Jacobian, on the single joint (26 states), one
// leg (78) and, when present, three legs (234). Prints wall time, steps and the ratio to dense.
//   build/bench/bench_linear_solver [simulated_ms=2000]
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "common/embedded.hpp"
#include "config/config.hpp"

using namespace phasmid;

int main(int argc, char** argv) {
  const double t_end = argc > 1 ? std::atof(argv[1]) : 2000.0;
  struct Variant { const char* name; solver::LinearSolverKind ls; };
  const Variant variants[] = {
      {"dense + AD Jacobian", solver::LinearSolverKind::Dense},
      {"KLU sparse + AD Jacobian", solver::LinearSolverKind::Klu},
  };
  std::printf("simulated time per run: %.0f ms (rtol/atol from each config)\n", t_end);
  for (const char* cfg_name : {"configs/single_joint_fti.toml", "configs/middle_leg_forward.toml", "configs/three_legs_tetrapod.toml"}) {
    if (!embedded::files().count(cfg_name)) continue;
    auto cfg = config::load_config(cfg_name);
    auto m = config::build_model(cfg);
    auto s = config::simulation_settings(cfg);
    std::printf("\n%s (%zu states)\n", cfg_name, m->num_states());
    double dense = 0;
    for (const Variant& v : variants) {
      solver::SolverOptions o = s.solver;
      o.integrator = solver::IntegratorKind::Bdf;
      o.partitioning = solver::Partitioning::Off;
      o.linear_solver = v.ls;
      solver::Simulator sim(*m, o);
      auto t0 = std::chrono::steady_clock::now();
      auto r = sim.run(m->parameters().values(), solver::output_grid(t_end, 10.0));
      double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (dense == 0) dense = wall;
      std::printf("  %-40s %8.2f s  %8ld steps  %6ld Jacobians   speed-up vs dense %.2fx\n", v.name, wall,
                  r.stats.steps, r.stats.jac_evals, dense / wall);
    }
  }
}
