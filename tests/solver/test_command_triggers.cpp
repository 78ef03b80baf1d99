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

using namespace phasmid;

namespace {
const char* kConfig = R"(
[model]
type = "leg"
leg = "middle"
direction_switch = true
motoneuron = "rate"

[[triggers]]
set = "middle.command.backward_ms"
event = "middle.touchdown"
after_ms = 1500

[[triggers]]
set = "middle.command.forward_ms"
event = "middle.liftoff"
after = "middle.command.backward_ms"
delay_ms = 200

[simulation]
rtol = 1e-6
atol = 1e-6
)";

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

TriggerRun run(const std::vector<std::string>& sets) {
  auto cfg = config::parse_config(kConfig, "triggers.toml");
  TriggerRun x;
  x.m = config::build_model(cfg, sets);
  solver::Simulator sim(*x.m, config::simulation_settings(cfg).solver);
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
