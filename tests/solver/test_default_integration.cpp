// The model kinds' default integration settings (OdeScenario defaults, chosen by
// bench/method_study.sh; docs/solver.md "Integrators") against a tight-tolerance
// reference, CVODES BDF at rtol = atol = 1e-10 as one system: every feature in ms within
// 0.01 ms, every one in deg within 0.01 deg. The single FTi joint as shipped
// (configs/single_joint_fti.toml, Dormand-Prince 5(4) at 1e-6 in phasmid's stepper, 9 s), the
// single joint at the setting of the Brian2 head-to-head, and the three legs with
// rate motoneurons at their kind's default (BDF per joint at 1e-7; 5 s, 2.5 s discarded); both
// three-leg models on two threads ([simulation] threads = 2: the windowed partitioned run,
// spiking at its default Dormand-Prince per joint at 1e-6).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "build_info.hpp"
#include "config/config.hpp"
#include "scenario/scenario.hpp"
#include "solver/integrator_kind.hpp"

using namespace phasmid;

namespace {

// gate_durations = false: only periods and angles (the Brian2 comparison's gate), the other
// durations printed.
void expect_default_matches_reference(const config::Config& cfg, const char* what, bool gate_durations = true) {
  auto scenario = config::build_scenario(cfg);
  const config::SimulationSettings defaults = config::simulation_settings(cfg, scenario.get());
  config::SimulationSettings ref = defaults;
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
    const bool is_period = f.name.size() >= 9 && f.name.compare(f.name.size() - 9, 9, "period_ms") == 0;
    if (!gate_durations && f.unit == "ms" && !is_period) {
      std::printf("  %s: %+.4f ms (not gated)\n", f.name.c_str(), f.value - want[f.name]);
      continue;
    }
    EXPECT_NEAR(f.value, want[f.name], 0.01) << what << ": " << f.name << " (" << f.unit << ")";
    ++gated;
  }
  std::printf("%s: %s at rtol %g, %zu features in ms and deg within 0.01 of BDF 1e-10\n", what,
              solver::integrator_name(defaults.solver.integrator).c_str(), defaults.solver.rtol,
              gated);
  EXPECT_GE(gated, 4u);
}

// The single joint's fastest setting at the Brian2 comparison's gate (docs/solver.md
// "Spiking cells apart"): the motoneurons, muscles and mechanics on Dormand-Prince at 1e-4, the
// CPG and interneurons on CVODES BDF at stiff_part_tol 1e-7; period and extremal angles within
// 0.01 ms and 0.01 deg. The flexion and extension durations (burst-located) are 0.19 ms off at
// this tolerance and within the gate only from 1e-6: not gated here. `extra`: more
// [simulation] lines.
config::Config single_joint_neurons_partition(const std::string& extra) {
  return config::parse_config(
      "[model]\ntype = \"single_joint\"\nleg = \"middle\"\njoint = \"fti\"\n"
      "[simulation]\nt_end_ms = 9000\ndiscard_ms = 2000\nintegrator = \"dopri5\"\nrtol = 1e-4\natol = 1e-4\n"
      "partitioned = \"neurons\"\nstiff_part_tol = 1e-7\n" + extra,
      "single_joint_neurons.toml");
}

}  // namespace

TEST(DefaultIntegration, SingleJointAsShippedMatchesTheTightReference) {
  auto cfg = config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/single_joint_fti.toml");
  auto scenario = config::build_scenario(cfg);
  EXPECT_EQ(config::simulation_settings(cfg, scenario.get()).solver.integrator, solver::IntegratorKind::Dopri5);
  expect_default_matches_reference(cfg, "single joint (spiking)");
}

TEST(DefaultIntegration, SingleJointNeuronsPartitionMatchesTheTightReference) {
  auto cfg = single_joint_neurons_partition("");
  auto scenario = config::build_scenario(cfg);
  ASSERT_EQ(config::simulation_settings(cfg, scenario.get()).solver.partitioning, solver::Partitioning::Neurons);
  expect_default_matches_reference(cfg, "single joint (spiking, neurons partition)", false);
}

// The same with the network part's potentials at atol 1e-4 mV (stiff_part_atol_by_unit; its rtol
// and other atol stay 1e-7): the middle of the interval of values that keep the gate.
TEST(DefaultIntegration, SingleJointNeuronsPartitionLooserNetworkPotentialsMatchTheTightReference) {
  auto cfg = single_joint_neurons_partition("stiff_part_atol_by_unit = { mV = 1e-4 }\n");
  auto scenario = config::build_scenario(cfg);
  ASSERT_EQ(config::simulation_settings(cfg, scenario.get()).solver.stiff_part_atol_by_unit.size(), 1u);
  expect_default_matches_reference(cfg, "single joint (spiking, neurons partition, network mV atol 1e-4)", false);
}

// The setting of the Brian2 head-to-head (docs/performance.md "phasmid vs Brian2"):
// phasmid's Dormand-Prince on the spiking part at 3.5e-5, the network part's potentials at atol
// 1e-4 mV; 3.5e-5 is the loosest tolerance of that ladder whose tighter rungs all meet the gate.
TEST(DefaultIntegration, SingleJointBrian2HeadToHeadSettingMatchesTheTightReference) {
  auto cfg = config::parse_config(
      "[model]\ntype = \"single_joint\"\nleg = \"middle\"\njoint = \"fti\"\n"
      "[simulation]\nt_end_ms = 9000\ndiscard_ms = 2000\nintegrator = \"dopri5\"\nrtol = 3.5e-5\natol = 3.5e-5\n"
      "partitioned = \"neurons\"\nstiff_part_tol = 1e-7\nstiff_part_atol_by_unit = { mV = 1e-4 }\n",
      "single_joint_head_to_head.toml");
  expect_default_matches_reference(cfg, "single joint (dopri5 3.5e-5, neurons partition, network mV 1e-4)", false);
}

TEST(DefaultIntegration, RateThreeLegsMatchTheTightReference) {
  auto cfg = config::parse_config(
      "[model]\ntype = \"three_legs\"\ngait = \"tetrapod\"\nmotoneuron = \"rate\"\n"
      "[simulation]\nt_end_ms = 5000\ndiscard_ms = 2500\n",
      "three_legs_rate.toml");
  expect_default_matches_reference(cfg, "three legs (rate)");
}

TEST(DefaultIntegration, ThreeLegsOnTwoThreadsMatchTheTightReference) {
  for (const char* mn : {"rate", "spiking"}) {
    auto cfg = config::parse_config(std::string("[model]\ntype = \"three_legs\"\ngait = \"tetrapod\"\nmotoneuron = \"") +
                                        mn + "\"\n[simulation]\nt_end_ms = 5000\ndiscard_ms = 2500\nthreads = 2\n",
                                    "three_legs_threads.toml");
    auto scenario = config::build_scenario(cfg);
    ASSERT_EQ(config::simulation_settings(cfg, scenario.get()).solver.threads, 2);
    expect_default_matches_reference(cfg, (std::string("three legs (") + mn + ", 2 threads)").c_str());
  }
}

// The fastest setting of the three legs with rate motoneurons (docs/performance.md "The 2013
// timings"): two threads in 1 ms windows with per-unit absolute tolerances, still within the
// gate of BDF 1e-10.
TEST(DefaultIntegration, RateThreeLegsFastestSettingMatchesTheTightReference) {
  auto cfg = config::parse_config(
      "[model]\ntype = \"three_legs\"\ngait = \"tetrapod\"\nmotoneuron = \"rate\"\n"
      "[simulation]\nt_end_ms = 5000\ndiscard_ms = 2500\nthreads = 2\nthread_window_ms = 1\n"
      "atol_by_unit = { \"1\" = 1e-6, mV = 1e-5 }\n",
      "three_legs_rate_fast.toml");
  auto scenario = config::build_scenario(cfg);
  const solver::SolverOptions o = config::simulation_settings(cfg, scenario.get()).solver;
  ASSERT_EQ(o.threads, 2);
  ASSERT_EQ(o.window_ms, 1.0);
  ASSERT_EQ(o.atol_by_unit.size(), 2u);
  expect_default_matches_reference(cfg, "three legs (rate, 2 threads, 1 ms windows, atol_by_unit)");
}
