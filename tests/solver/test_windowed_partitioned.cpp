// The windowed partitioned run (SolverOptions::threads >= 2, solver/partitioned_simulator.hpp):
// parts step concurrently within windows, reading each other's angles from snapshots taken at
// the window's start. Its numbers depend on the window, never on the thread count or on which
// thread stepped which part: runs with 2, 3 and 8 threads and repeated runs agree bit for bit
// (events, outputs, step counts), also where parts complete windows ahead of the slowest while
// a thread would otherwise wait (three and eight threads on nine parts). Triggered commands (roll-backs across a window) agree with
// the whole system as the sequential partitioned run does (tests/solver/test_command_triggers.cpp).
// The accuracy gate on two threads (features within 0.01 ms / 0.01 deg of BDF 1e-10) is in
// tests/solver/test_default_integration.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "features/features.hpp"
#include "middle_leg_trigger_config.hpp"
#include "model/leg_network.hpp"
#include "model/network_builder.hpp"
#include "solver/simulator.hpp"

using namespace phasmid;

namespace {

solver::SolveResult run_three_legs(model::MotoneuronModel mn, int threads, double t_end) {
  model::ThreeLegOptions t;
  t.motoneuron = mn;
  auto m = model::build_three_leg_model(t);
  solver::SolverOptions o;
  o.rtol = o.atol = 1e-6;
  o.integrator = mn == model::MotoneuronModel::Spiking ? solver::IntegratorKind::Dopri5 : solver::IntegratorKind::Bdf;
  o.partitioning = solver::Partitioning::On;
  o.threads = threads;
  return solver::Simulator(*m, o).run(m->parameters().values(), solver::output_grid(t_end, 5.0),
                                      features::feature_roots(*m));
}

void expect_bitwise_equal(const solver::SolveResult& a, const solver::SolveResult& b, const char* what) {
  EXPECT_EQ(a.stats.steps, b.stats.steps) << what;
  EXPECT_EQ(a.stats.rhs_evals, b.stats.rhs_evals) << what;
  ASSERT_EQ(a.events.size(), b.events.size()) << what;
  for (size_t i = 0; i < a.events.size(); ++i) {
    EXPECT_EQ(a.events[i].t, b.events[i].t) << what << " event " << i;
    EXPECT_EQ(a.events[i].root, b.events[i].root) << what << " event " << i;
    EXPECT_EQ(a.events[i].y, b.events[i].y) << what << " event " << i;
  }
  ASSERT_EQ(a.y.size(), b.y.size()) << what;
  size_t differing = 0;
  for (size_t i = 0; i < a.y.size(); ++i) differing += a.y[i] != b.y[i];
  EXPECT_EQ(differing, 0u) << what;
}

}  // namespace

TEST(WindowedPartitioned, SameNumbersForAnyThreadCount) {
  for (auto mn : {model::MotoneuronModel::Rate, model::MotoneuronModel::Spiking}) {
    const double t_end = mn == model::MotoneuronModel::Rate ? 2000.0 : 600.0;
    const solver::SolveResult two = run_three_legs(mn, 2, t_end);
    EXPECT_EQ(two.stats.integrators, 9);
    EXPECT_GT(two.events.size(), 10u);
    expect_bitwise_equal(two, run_three_legs(mn, 2, t_end), "2 threads, again");
    expect_bitwise_equal(two, run_three_legs(mn, 3, t_end), "3 threads");
    expect_bitwise_equal(two, run_three_legs(mn, 8, t_end), "8 threads");
  }
}

// Triggered commands on two threads: the crossing is found inside a window, fed after it, and
// the parts beyond the command time go back to it. Same commands as the whole system within
// the tolerances of CommandTriggers.PartitionedRunTriggersTheSameCommands.
TEST(WindowedPartitioned, TriggersFireTheSameCommands) {
  const std::string text = test::middle_leg_trigger_config(1500, 200);
  for (double rtol : {1e-8, 1e-6}) {
    const double tol = rtol < 1e-7 ? 0.02 : 0.3;
    std::map<std::string, double> t_ms[2];
    for (int threads : {1, 2}) {
      auto cfg = config::parse_config(text, "triggers.toml");
      auto m = config::build_model(cfg, {});
      solver::SolverOptions o = config::simulation_settings(cfg).solver;
      o.rtol = o.atol = rtol;
      o.partitioning = threads == 1 ? solver::Partitioning::Off : solver::Partitioning::On;
      o.threads = threads;
      auto r = solver::Simulator(*m, o).run(m->parameters().values(), solver::output_grid(3000, 5.0),
                                            features::feature_roots(*m));
      ASSERT_EQ(r.commands.size(), 2u) << threads;
      for (const auto& c : r.commands) t_ms[threads - 1][m->parameters().at(c.parameter).name] = c.t_ms;
    }
    for (const char* name : {"middle.command.backward_ms", "middle.command.forward_ms"}) {
      std::printf("rtol %g: %s windowed %.4f ms, whole %.4f ms\n", rtol, name, t_ms[1][name], t_ms[0][name]);
      EXPECT_NEAR(t_ms[1][name], t_ms[0][name], tol) << name;
    }
  }
}
