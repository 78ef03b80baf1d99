// Knops 2013 Section 3.2.2 (Figs. 3.10-3.12): the SF/SB command network of Fig. 3.11 switches
// the middle leg between forward and backward stepping by presynaptic inhibition only, and
// sideward stepping holds the ThC joint while beta and gamma keep stepping. The tests use
// the configs' model with earlier command times (4 s backward window instead of 3.25 s) and
// rtol = atol = 1e-6 to stay affordable.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "config/config.hpp"
#include "features/features.hpp"

using namespace phasmid;

namespace {
struct SimRun {
  std::unique_ptr<model::OdeModel> m;
  solver::SolveResult r;
};
SimRun run(const std::string& config, double t_end, const std::vector<std::string>& sets) {
  auto cfg = config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/" + config);
  SimRun x;
  x.m = config::build_model(cfg, sets);
  auto s = config::simulation_settings(cfg);
  s.solver.rtol = s.solver.atol = 1e-6;
  solver::Simulator sim(*x.m, s.solver);
  x.r = sim.run(x.m->parameters().values(), solver::output_grid(t_end, 5.0), features::feature_roots(*x.m));
  return x;
}
// Features of the window [t0, t1] (events outside it are dropped).
std::map<std::string, double> window(const SimRun& x, double t0, double t1) {
  solver::SolveResult r = x.r;
  r.events.erase(std::remove_if(r.events.begin(), r.events.end(), [&](const solver::Event& e) { return e.t > t1; }),
                 r.events.end());
  features::FeatureOptions fo;
  fo.discard_ms = t0;
  std::map<std::string, double> f;
  for (auto& v : features::compute_features(*x.m, r, fo)) f[v.name] = v.value;
  return f;
}
}  // namespace

TEST(WalkingSwitch, BackwardSteppingReversesRetractionDuringStance) {
  // Fig. 3.10 with the switches at 3000 ms (backward) and 6000 ms (forward again).
  SimRun x = run("middle_leg_switch.toml", 8500, {"middle.command.backward_ms=3000", "middle.command.forward_ms=6000"});
  auto fwd = window(x, 1500, 3000), bwd = window(x, 3600, 6000), fwd2 = window(x, 6600, 8500);
  ASSERT_TRUE(fwd.count("middle.thc.stance_change_deg") && bwd.count("middle.thc.stance_change_deg") &&
              fwd2.count("middle.thc.stance_change_deg"));
  EXPECT_GT(fwd["middle.thc.stance_change_deg"], 50.0);   // retraction during stance
  EXPECT_LT(bwd["middle.thc.stance_change_deg"], -30.0);  // protraction during stance
  EXPECT_GT(fwd2["middle.thc.stance_change_deg"], 50.0);
  // The LD and FE systems run on unchanged (Rosenbaum et al. 2010): same step period.
  EXPECT_NEAR(bwd["middle.step_period_ms"], fwd["middle.step_period_ms"], 10.0);
  EXPECT_NEAR(bwd["middle.step_period_ms"], 510.0, 15.0);
}

TEST(WalkingSwitch, SidewardHoldsThcWhileBetaAndGammaStep) {
  SimRun x = run("middle_leg_sideward.toml", 5000, {"middle.command.sideward_ms=2500"});
  const auto& ch = x.m->angles();
  size_t a = 0;
  for (auto& c : ch)
    if (c.leg == "middle" && c.joint == "thc") a = c.angle_state;
  double lo = 1e9, hi = -1e9;
  for (size_t k = 0; k < x.r.t.size(); ++k)
    if (x.r.t[k] >= 3000) {
      double v = x.r.state(k, a) * 180 / M_PI;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  EXPECT_LT(hi - lo, 5.0);  // alpha held (forward: 30-117 deg)
  auto f = window(x, 3000, 5000);
  EXPECT_NEAR(f["middle.ctr.period_ms"], 510.0, 15.0);  // beta keeps stepping
  EXPECT_NEAR(f["middle.fti.period_ms"], 510.0, 15.0);  // gamma keeps stepping
  EXPECT_GT(f["middle.fti.angle_max_deg"] - f["middle.fti.angle_min_deg"], 40.0);
}
