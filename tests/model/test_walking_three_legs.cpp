// Knops 2013 Sections 2.5.4 and 3.3 (Figs. 2.14, 3.19-3.23): three ipsilateral legs
// (72 neurons, 234 equations) with intersegmental coupling; tetrapod and tripod from the
// start times. The tests integrate 4.5 s of the 9 s configs (the legs start between 1500 and
// 1840 ms; features after 2500 ms, i.e. four steps) on a 5 ms output grid.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "config/config.hpp"
#include "features/features.hpp"

using namespace phasmid;

namespace {
std::map<std::string, double> walk(const std::string& config, const std::vector<std::string>& sets = {},
                                   size_t* n_states = nullptr) {
  auto cfg = config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/" + config);
  auto m = config::build_model(cfg, sets);
  if (n_states) *n_states = m->num_states();
  auto s = config::simulation_settings(cfg);
  solver::Simulator sim(*m, s.solver);
  auto r = sim.run(m->parameters().values(), solver::output_grid(4500, 5.0), features::feature_roots(*m));
  features::FeatureOptions fo;
  fo.discard_ms = 2500;
  std::map<std::string, double> f;
  for (auto& x : features::compute_features(*m, r, fo)) f[x.name] = x.value;
  return f;
}
// Circular distance of two phases in [0, 1).
double cdist(double a, double b) {
  double d = std::fabs(a - b);
  d -= std::floor(d);
  return std::min(d, 1.0 - d);
}
}  // namespace

TEST(ThreeLegs, TetrapodPeriodAndMetachronalLags) {
  size_t n = 0;
  auto f = walk("three_legs_tetrapod.toml", {}, &n);
  // Section 2.6: 234 equations for the 72 neurons, muscles and joints; phasmid adds one
  // start/transition command neuron per leg (<leg>.ld_hold, 2 states each).
  EXPECT_EQ(n, 234u + 3u * 2u);
  for (const char* leg : {"front", "middle", "hind"}) {
    ASSERT_TRUE(f.count(std::string(leg) + ".step_period_ms")) << leg;
    EXPECT_NEAR(f[std::string(leg) + ".step_period_ms"], 510.0, 15.0) << leg;  // T_4pod = 510 ms
  }
  // Figs. 2.17, 3.21: hind -> middle -> front, each a third of the period later.
  EXPECT_LT(cdist(f["phase_lag.hind_to_middle"], 1.0 / 3), 0.07);
  EXPECT_LT(cdist(f["phase_lag.middle_to_front"], 1.0 / 3), 0.07);
  EXPECT_EQ(f["gait_class"], 1.0);
}

TEST(ThreeLegs, TripodPeriodFrontHindInPhaseMiddleAntiphase) {
  auto f = walk("three_legs_tripod.toml");
  for (const char* leg : {"front", "middle", "hind"})
    EXPECT_NEAR(f[std::string(leg) + ".step_period_ms"], 442.0, 10.0) << leg;  // T_3pod = 442 ms
  EXPECT_LT(cdist(f["phase_lag.hind_to_front"], 0.0), 0.05);   // front and hind in phase
  EXPECT_LT(cdist(f["phase_lag.hind_to_middle"], 0.5), 0.1);   // middle in antiphase
  EXPECT_EQ(f["gait_class"], 2.0);
}
