// Continuation of the single FTi joint network (configs/continue_single_joint_gapp.toml,
// configs/continue_single_joint_vhh.toml; docs/continuation.md) against what a sweep of the
// same parameter finds: each branch point's period and extremal angles agree with
// Scenario::evaluate_features (what `phasmid sweep` computes per point: one run from the
// model's initial state, a transient discarded) within 0.1 ms and 0.1 deg, and the branch in
// the CPGs' inactivation midpoint ends where the rhythm is lost, with the period growing
// without bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "build_info.hpp"
#include "config/config.hpp"
#include "config/continuation_section.hpp"
#include "continuation/continuation.hpp"
#include "model/ode_model.hpp"

using namespace phasmid;

namespace {

config::Config shipped(const std::string& name) {
  return config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/" + name);
}

double value(const std::vector<features::Feature>& fs, const std::string& name) {
  for (const auto& f : fs)
    if (f.name == name) return f.value;
  return NAN;
}

scenario::RunSettings sweep_run(const config::Config& cfg, const scenario::Scenario& s) {
  scenario::RunSettings r = config::simulation_settings(cfg, &s);
  r.t_end_ms = 9000;  // a long transient, so that the sweep's cycle has converged too
  r.discard_ms = 6000;
  r.solver.progress = false;
  return r;
}

TEST(SingleJointContinuation, BranchInExtensorDriveAgreesWithTheSweep) {
  config::Config cfg = shipped("continue_single_joint_gapp.toml");
  auto scenario = config::build_scenario(cfg);
  const model::OdeModel& m = *scenario->ode_model();
  auto o = config::continuation_options(cfg, m, config::simulation_settings(cfg, scenario.get()));
  o.start = 0.16;  // a stretch of the shipped range, to keep the test short
  o.end = 0.21;
  o.initial_step = o.max_step = 0.02;
  const continuation::Branch b = continuation::continue_cycles(m, m.parameters().values(), o);
  ASSERT_GE(b.points.size(), 3u);
  EXPECT_EQ(b.special.back().kind, "range_end");
  const size_t k = m.parameters().index(o.parameter);
  const auto run = sweep_run(cfg, *scenario);
  auto col = [&](const std::string& name) {
    return std::find(b.feature_names.begin(), b.feature_names.end(), name) - b.feature_names.begin();
  };
  for (const auto& q : b.points) {
    std::vector<double> p = m.parameters().values();
    p[k] = q.parameter;
    const auto f = scenario->evaluate_features(p, run);
    EXPECT_TRUE(q.stable);
    EXPECT_NEAR(q.period_ms, value(f, "period_ms"), 0.1) << "g_app " << q.parameter;
    EXPECT_NEAR(q.features[col("period_ms")], value(f, "period_ms"), 0.1) << "g_app " << q.parameter;
    for (const char* a : {"middle.fti.angle_min_deg", "middle.fti.angle_max_deg"})
      EXPECT_NEAR(q.features[col(a)], value(f, a), 0.1) << a << " at g_app " << q.parameter;
    EXPECT_NEAR(q.features[col("middle.fti.flexion_fraction")], value(f, "middle.fti.flexion_fraction"), 1e-3);
  }
}

// Raising the CPGs' inactivation midpoint from -44 mV the period grows without bound near
// V_hh = -41.75 mV, the cycle stable up to there (a saddle-node on the cycle or a homoclinic
// orbit): the rhythm is lost long before the printed -30 mV. A sweep just below has the
// rhythm, just above none.
TEST(SingleJointContinuation, RhythmLostInInactivationMidpointWithUnboundedPeriod) {
  config::Config cfg = shipped("continue_single_joint_vhh.toml");
  auto scenario = config::build_scenario(cfg);
  const model::OdeModel& m = *scenario->ode_model();
  auto o = config::continuation_options(cfg, m, config::simulation_settings(cfg, scenario.get()));
  o.start = -42.3;  // the last part of the shipped branch
  o.initial_step = o.max_step = 0.2;
  const continuation::Branch b = continuation::continue_cycles(m, m.parameters().values(), o);
  ASSERT_FALSE(b.special.empty());
  const auto& end = b.special.back();
  EXPECT_EQ(end.kind, "period_unbounded");
  EXPECT_NEAR(end.parameter, -41.75, 0.01);
  EXPECT_GT(end.period_ms, 585.0);
  for (const auto& q : b.points) EXPECT_TRUE(q.stable) << "V_hh " << q.parameter;
  const size_t k = m.parameters().index("cpg.V_hh");
  const auto run = sweep_run(cfg, *scenario);
  std::vector<double> p = m.parameters().values();
  p[k] = end.parameter - 0.05;
  EXPECT_TRUE(std::isfinite(value(scenario->evaluate_features(p, run), "period_ms")));
  p[k] = end.parameter + 0.1;
  EXPECT_FALSE(std::isfinite(value(scenario->evaluate_features(p, run), "period_ms")));
}

}  // namespace
