// Wall time of walking simulations next to the dissertation's compute times (Knops 2013,
// Section 2.6: 2 s for one joint, 15 s for one leg, 180 s for three legs, each for 9 s of
// walking). Usage: bench_walking [T_END_MS=9000] [models=joint,leg,three] [dense|band|klu|auto]
// Prints one line per model: states, simulated ms, wall s, steps, RHS and Jacobian
// evaluations, and the ratio to the 2013 time scaled to the simulated duration.
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "features/features.hpp"
#include "model/leg_network.hpp"
#include "model/network_builder.hpp"
#include "solver/simulator.hpp"

using namespace phasmid;

int main(int argc, char** argv) {
  const double t_end = argc > 1 ? std::atof(argv[1]) : 9000.0;
  const std::string which = argc > 2 ? argv[2] : "joint,leg,three";
  const std::string ls = argc > 3 ? argv[3] : "auto";
  solver::SolverOptions so;
  so.rtol = so.atol = 1e-6;  // the three-leg configs' tolerance
  if (ls == "dense") so.linear_solver = solver::LinearSolverKind::Dense;
  if (ls == "band") so.linear_solver = solver::LinearSolverKind::Band;
  if (ls == "klu") so.linear_solver = solver::LinearSolverKind::Klu;
  struct Case {
    const char* key;
    const char* label;
    double t2013_s;  // for 9 s of walking
  };
  const Case cases[] = {{"joint", "single joint (FTi)", 2.0}, {"leg", "middle leg", 15.0}, {"three", "three legs (tetrapod)", 180.0}};
  std::printf("# bench_walking: %.0f ms simulated, rtol = atol = %g, %s linear solver\n", t_end, so.rtol, ls.c_str());
  std::printf("%-24s %7s %8s %8s %8s %8s %9s %7s %14s %8s\n", "model", "states", "sim_ms", "wall_s", "cpu_s", "steps",
              "rhs", "jac", "2013_s(scaled)", "ratio");
  for (const Case& c : cases) {
    if (which.find(c.key) == std::string::npos) continue;
    std::unique_ptr<model::NetworkModel> m;
    if (std::string(c.key) == "joint") m = model::build_single_joint_model("middle", model::JointType::Fti);
    else if (std::string(c.key) == "leg") {
      model::LegOptions o;
      o.thc_set = "A.17";
      m = model::build_leg_model("middle", o);
    } else
      m = model::build_three_leg_model({});
    solver::Simulator sim(*m, so);
    auto t0 = std::chrono::steady_clock::now();
    std::clock_t c0 = std::clock();
    auto r = sim.run(m->parameters().values(), solver::output_grid(t_end, 5.0), features::feature_roots(*m));
    double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
    double ref = c.t2013_s * t_end / 9000.0;
    std::printf("%-24s %7zu %8.0f %8.2f %8.2f %8ld %9ld %7ld %14.1f %8.3f\n", c.label, m->num_states(), t_end, wall, cpu,
                r.stats.steps, r.stats.rhs_evals, r.stats.jac_evals, ref, wall / ref);
  }
  return 0;
}
