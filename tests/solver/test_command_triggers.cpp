// Command times triggered by events (model::CommandTrigger, [[triggers]]): the simulator finds
// the event and switches the command exactly there, so a triggered run equals a run with the
// found times given as fixed times (--set), and a delay is added to the event time. A middle
// leg with the direction switch (Fig. 3.11, rate motoneurons for speed): backward stepping at
// a touch-down, forward again 200 ms after the next lift-off.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "features/features.hpp"
#include "middle_leg_trigger_config.hpp"

using namespace phasmid;

namespace {
// Backward from the first touch-down after 1500 ms, forward 200 ms after the next lift-off.
const std::string kConfig = test::middle_leg_trigger_config(1500, 200) + "\n[simulation]\nrtol = 1e-6\natol = 1e-6\n";

struct TriggerRun {
  std::unique_ptr<model::OdeModel> m;
  solver::SolveResult r;
  size_t beta_root = 0;
  std::vector<double> crossings(int direction, double t0) const {
    std::vector<double> out;
    for (const auto& e : r.events)
      if (e.root == beta_root && e.direction == direction && e.t >= t0) out.push_back(e.t);
    return out;
  }
};

// partitioned / rtol: the integration (SolverOptions::partitioning On / Off; rtol = atol, 0: the config's).
TriggerRun run(const std::vector<std::string>& sets, bool partitioned = true, double rtol = 0.0) {
  auto cfg = config::parse_config(kConfig, "triggers.toml");
  TriggerRun x;
  x.m = config::build_model(cfg, sets);
  solver::SolverOptions o = config::simulation_settings(cfg).solver;
  o.partitioning = partitioned ? solver::Partitioning::On : solver::Partitioning::Off;
  if (rtol > 0) o.rtol = o.atol = rtol;
  solver::Simulator sim(*x.m, o);
  auto roots = features::feature_roots(*x.m);
  x.beta_root = x.m->angles().size();  // the leg's beta root follows the angle channels
  EXPECT_EQ(roots[x.beta_root].state, x.m->state_index("middle.ctr.beta"));
  x.r = sim.run(x.m->parameters().values(), solver::output_grid(3000, 5.0), roots);
  return x;
}

double resolved(const TriggerRun& x, const std::string& name) {
  for (const auto& c : x.r.commands)
    if (x.m->parameters().at(c.parameter).name == name) return c.t_ms;
  return NAN;
}
}  // namespace

TEST(CommandTriggers, TriggeredRunEqualsFixedRunAtTheFoundTimes) {
  TriggerRun trig = run({});
  const double t_bwd = resolved(trig, "middle.command.backward_ms"), t_fwd = resolved(trig, "middle.command.forward_ms");
  ASSERT_FALSE(std::isnan(t_bwd));
  ASSERT_FALSE(std::isnan(t_fwd));
  // Backward at the first touch-down after 1500 ms, located by the same root function.
  auto td = trig.crossings(-1, 1500), lo = trig.crossings(+1, t_bwd);
  ASSERT_FALSE(td.empty());
  ASSERT_FALSE(lo.empty());
  EXPECT_NEAR(t_bwd, td[0], 1e-9);
  EXPECT_NEAR(t_fwd, lo[0] + 200, 1e-9);  // forward 200 ms after the next lift-off
  EXPECT_LT(t_fwd, 3000);
  std::printf("backward at %.3f ms (touch-down), forward at %.3f ms (lift-off %.3f + 200); %zu touch-downs\n", t_bwd,
              t_fwd, lo[0], trig.crossings(-1, 0).size());

  char b[64], f[64];
  std::snprintf(b, sizeof b, "middle.command.backward_ms=%.17g", t_bwd);
  std::snprintf(f, sizeof f, "middle.command.forward_ms=%.17g", t_fwd);
  TriggerRun fixed = run({b, f});
  EXPECT_TRUE(fixed.r.commands.empty());
  EXPECT_TRUE(fixed.m->triggers().empty());
  for (int dir : {-1, +1}) {
    auto a = trig.crossings(dir, 0), c = fixed.crossings(dir, 0);
    ASSERT_EQ(a.size(), c.size()) << dir;
    for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], c[i], 0.5) << "crossing " << i << " direction " << dir;
  }
}

// Events before the earliest time, or before the command named by `after` fired, do not count.
TEST(CommandTriggers, NotArmedBeforeTheEarliestTime) {
  TriggerRun trig = run({"middle.command.backward_ms=2600"});  // fixed: the forward trigger waits for it
  const double t_fwd = resolved(trig, "middle.command.forward_ms");
  auto lo = trig.crossings(+1, 2600);
  ASSERT_FALSE(lo.empty());
  std::printf("backward fixed at 2600 ms: forward at %.3f ms (lift-off %.3f + 200)\n", t_fwd, lo[0]);
  EXPECT_NEAR(t_fwd, lo[0] + 200, 1e-9);  // not 200 ms after the lift-offs before 2600 ms
  EXPECT_TRUE(std::isnan(resolved(trig, "middle.command.backward_ms")));
}

// The partitioned integration (one integrator per joint) resolves triggers too: a command at
// tau becomes a point where all joints restart, joints already past it go back to tau. At
// rtol 1e-8 its command times and touch-downs / lift-offs equal the whole system's within
// 0.02 ms (the accuracy test of tests/solver/test_partitioned_simulator.cpp), at 1e-6 within
// 0.3 ms (each integration's own error there is up to 0.13 ms, as measured in that test).
TEST(CommandTriggers, PartitionedRunTriggersTheSameCommands) {
  for (double rtol : {1e-8, 1e-6}) {
    const double tol = rtol < 1e-7 ? 0.02 : 0.3;
    TriggerRun parts = run({}, true, rtol), whole = run({}, false, rtol);
    EXPECT_GT(parts.r.stats.integrators, 1);
    EXPECT_EQ(whole.r.stats.integrators, 1);
    ASSERT_EQ(parts.r.commands.size(), 2u);
    ASSERT_EQ(whole.r.commands.size(), 2u);
    for (const char* name : {"middle.command.backward_ms", "middle.command.forward_ms"}) {
      std::printf("rtol %g: %s partitioned %.4f ms, whole %.4f ms\n", rtol, name, resolved(parts, name), resolved(whole, name));
      EXPECT_NEAR(resolved(parts, name), resolved(whole, name), tol) << name;
    }
    for (int dir : {-1, +1}) {
      auto a = parts.crossings(dir, 0), c = whole.crossings(dir, 0);
      ASSERT_EQ(a.size(), c.size()) << dir;
      for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], c[i], tol) << "crossing " << i << " direction " << dir;
    }
  }
}
