// The model kinds' integration (scenario/kinds/integration.hpp, docs/solver.md "How each kind
// integrates"): what each kind resolves a request to, and its defaults against a tight
// reference, CVODES BDF at rtol = atol = 1e-10 as one system: every feature in ms within
// 0.01 ms, every one in deg within 0.01 deg. The single FTi joint as shipped
// (configs/single_joint_fti.toml, 9 s), the three legs with spiking and with rate motoneurons
// at their kinds' defaults (5 s, 2.5 s discarded), both on two threads ([simulation.expert]
// threads = 2: the windowed partitioned run), and the rate three legs at their fastest expert
// setting. tests/scenario/configs_accuracy.test.sh checks every shipped config the same way.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "build_info.hpp"
#include "config/config.hpp"
#include "scenario/kinds/integration.hpp"
#include "scenario/scenario.hpp"
#include "solver/integrator_kind.hpp"

using namespace phasmid;

namespace {

solver::SolverOptions resolved(const std::string& text) {
  const config::Config cfg = config::parse_config(text, "kind.toml");
  auto scenario = config::build_scenario(cfg);
  return config::simulation_settings(cfg, scenario.get()).solver;
}

void expect_default_matches_reference(const config::Config& cfg, const char* what) {
  auto scenario = config::build_scenario(cfg);
  const config::SimulationSettings defaults = config::simulation_settings(cfg, scenario.get());
  config::SimulationSettings ref = defaults;
  ref.solver = solver::SolverOptions{};
  ref.solver.integrator = solver::IntegratorKind::Bdf;
  ref.solver.rtol = ref.solver.atol = 1e-10;
  ref.solver.partitioning = solver::Partitioning::Off;
  ref.solver.stiff_part_atol_by_unit.clear();  // only with the neurons partition (SolverOptions::validate)
  const auto p = scenario->parameters().values();
  std::map<std::string, double> want;
  for (const auto& f : scenario->evaluate_features(p, ref)) want[f.name] = f.value;
  size_t gated = 0;
  for (const auto& f : scenario->evaluate_features(p, defaults)) {
    if (f.unit != "ms" && f.unit != "deg") continue;
    ASSERT_TRUE(want.count(f.name)) << f.name;
    if (std::isnan(want[f.name])) continue;
    EXPECT_NEAR(f.value, want[f.name], 0.01) << what << ": " << f.name << " (" << f.unit << ")";
    ++gated;
  }
  std::printf("%s: %s at rtol %g, %zu features in ms and deg within 0.01 of BDF 1e-10\n", what,
              solver::integrator_name(defaults.solver.integrator).c_str(), defaults.solver.rtol, gated);
  EXPECT_GE(gated, 4u);
}

const std::string kSingleJoint = "[model]\ntype = \"single_joint\"\nleg = \"middle\"\njoint = \"fti\"\n";

}  // namespace

TEST(DefaultIntegration, SpikingNetworksRunTheirSpikingCellsApartCompiled) {
  const solver::SolverOptions o = resolved(kSingleJoint);
  EXPECT_EQ(o.partitioning, solver::Partitioning::Neurons);
  EXPECT_EQ(o.integrator, solver::IntegratorKind::Dopri5);
  EXPECT_TRUE(o.compiled_rhs);
  EXPECT_EQ(o.rtol, 3e-6);
  EXPECT_EQ(o.atol, 3e-6);
  EXPECT_NEAR(o.stiff_part_tol, 1e-8, 1e-20);
  ASSERT_EQ(o.stiff_part_atol_by_unit.size(), 1u);
  EXPECT_EQ(o.stiff_part_atol_by_unit[0].first, "mV");
  EXPECT_NEAR(o.stiff_part_atol_by_unit[0].second, 1e-5, 1e-17);
  EXPECT_EQ(o.threads, 1);
}

// A user's rtol/atol tighten (or loosen) every part by the same factor; a named integrator or
// thread count gives the kind's setting for it; an expert key replaces that one choice.
TEST(DefaultIntegration, TheKindMapsAGivenToleranceOntoItsParts) {
  const solver::SolverOptions t = resolved(kSingleJoint + "[simulation]\nrtol = 3e-7\natol = 3e-6\n");
  EXPECT_EQ(t.partitioning, solver::Partitioning::Neurons);
  EXPECT_EQ(t.rtol, 3e-7);
  EXPECT_EQ(t.atol, 3e-6);
  EXPECT_NEAR(t.stiff_part_tol, 1e-9, 1e-21);
  ASSERT_EQ(t.stiff_part_atol_by_unit.size(), 1u);
  EXPECT_NEAR(t.stiff_part_atol_by_unit[0].second, 1e-5, 1e-18);

  const solver::SolverOptions bdf = resolved(kSingleJoint + "[simulation]\nintegrator = \"cvodes_bdf\"\n");
  EXPECT_EQ(bdf.integrator, solver::IntegratorKind::Bdf);
  EXPECT_EQ(bdf.partitioning, solver::Partitioning::Off);
  EXPECT_EQ(bdf.rtol, 1e-8);

  const solver::SolverOptions two = resolved("[model]\ntype = \"three_legs\"\n[simulation]\n[simulation.expert]\nthreads = 2\n");
  EXPECT_EQ(two.partitioning, solver::Partitioning::On);
  EXPECT_EQ(two.integrator, solver::IntegratorKind::Dopri5);
  EXPECT_EQ(two.rtol, 1e-6);

  const solver::SolverOptions expert =
      resolved(kSingleJoint + "[simulation]\n[simulation.expert]\nnetwork_tol = 3e-7\ncompiled_rhs = false\n");
  EXPECT_EQ(expert.stiff_part_tol, 3e-7);
  EXPECT_FALSE(expert.compiled_rhs);
  EXPECT_EQ(expert.rtol, 3e-6);

  const solver::SolverOptions rate = resolved("[model]\ntype = \"three_legs\"\nmotoneuron = \"rate\"\n");
  EXPECT_EQ(rate.integrator, solver::IntegratorKind::Bdf);
  EXPECT_EQ(rate.partitioning, solver::Partitioning::On);
  EXPECT_EQ(rate.rtol, 1e-7);
  EXPECT_FALSE(rate.compiled_rhs);

  const solver::SolverOptions mech = resolved("[model]\ntype = \"mechanical_joint\"\n[simulation]\nrtol = 1e-9\n");
  EXPECT_EQ(mech.integrator, solver::IntegratorKind::Bdf);
  EXPECT_EQ(mech.partitioning, solver::Partitioning::Off);
  EXPECT_EQ(mech.rtol, 1e-9);
}

TEST(DefaultIntegration, SingleJointAsShippedMatchesTheTightReference) {
  auto cfg = config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/single_joint_fti.toml");
  expect_default_matches_reference(cfg, "single joint (spiking)");
}

TEST(DefaultIntegration, ThreeLegsMatchTheTightReference) {
  for (const char* mn : {"rate", "spiking"}) {
    auto cfg = config::parse_config(std::string("[model]\ntype = \"three_legs\"\ngait = \"tetrapod\"\nmotoneuron = \"") +
                                        mn + "\"\n[simulation]\nt_end_ms = 5000\ndiscard_ms = 2500\n",
                                    "three_legs.toml");
    expect_default_matches_reference(cfg, (std::string("three legs (") + mn + ")").c_str());
  }
}

TEST(DefaultIntegration, ThreeLegsOnTwoThreadsMatchTheTightReference) {
  for (const char* mn : {"rate", "spiking"}) {
    auto cfg = config::parse_config(std::string("[model]\ntype = \"three_legs\"\ngait = \"tetrapod\"\nmotoneuron = \"") +
                                        mn + "\"\n[simulation]\nt_end_ms = 5000\ndiscard_ms = 2500\n"
                                             "[simulation.expert]\nthreads = 2\n",
                                    "three_legs_threads.toml");
    auto scenario = config::build_scenario(cfg);
    ASSERT_EQ(config::simulation_settings(cfg, scenario.get()).solver.threads, 2);
    expect_default_matches_reference(cfg, (std::string("three legs (") + mn + ", 2 threads)").c_str());
  }
}

// The fastest expert setting of the three legs with rate motoneurons: two threads in 1 ms
// windows with absolute tolerances by unit, still within the gate of BDF 1e-10.
TEST(DefaultIntegration, RateThreeLegsFastestSettingMatchesTheTightReference) {
  auto cfg = config::parse_config(
      "[model]\ntype = \"three_legs\"\ngait = \"tetrapod\"\nmotoneuron = \"rate\"\n"
      "[simulation]\nt_end_ms = 5000\ndiscard_ms = 2500\n"
      "[simulation.expert]\nthreads = 2\nwindow_ms = 1\natol_by_unit = { \"1\" = 1e-6, mV = 1e-5 }\n",
      "three_legs_rate_fast.toml");
  auto scenario = config::build_scenario(cfg);
  const solver::SolverOptions o = config::simulation_settings(cfg, scenario.get()).solver;
  ASSERT_EQ(o.threads, 2);
  ASSERT_EQ(o.window_ms, 1.0);
  ASSERT_EQ(o.atol_by_unit.size(), 2u);
  expect_default_matches_reference(cfg, "three legs (rate, 2 threads, 1 ms windows, atol_by_unit)");
}
