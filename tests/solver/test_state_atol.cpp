// Absolute tolerances by a state's unit ([simulation] atol_by_unit, SolverOptions::atol_by_unit):
// the integrators take them (a looser one for the membrane potentials takes fewer steps, the
// same value as atol reproduces the scalar run bit for bit), in the whole-system and the
// partitioned run, and for the network part of the neurons partition on its own
// (stiff_part_atol_by_unit); runs with sensitivities and bad values are refused.
#include <gtest/gtest.h>

#include <string>

#include "common/error.hpp"
#include "config/config.hpp"
#include "model/leg_network.hpp"
#include "model/network_builder.hpp"
#include "solver/simulator.hpp"

using namespace phasmid;

namespace {

solver::SolveResult run_leg(solver::Partitioning partitioning, const std::vector<std::pair<std::string, double>>& by_unit) {
  model::LegOptions l;
  l.thc_set = "A.17";
  l.motoneuron = model::MotoneuronModel::Rate;
  auto m = model::build_leg_model("middle", l);
  solver::SolverOptions o;
  o.rtol = o.atol = 1e-7;
  o.partitioning = partitioning;
  o.atol_by_unit = by_unit;
  return solver::Simulator(*m, o).run(m->parameters().values(), solver::output_grid(1500.0, 5.0));
}

// The single joint, spiking, partitioned = "neurons": its network part runs CVODES BDF at
// stiff_part_tol, with stiff_part_atol_by_unit as its atol by unit.
solver::SolveResult run_neurons_partition(const std::vector<std::pair<std::string, double>>& stiff_by_unit) {
  auto cfg = config::parse_config(
      "[model]\ntype = \"single_joint\"\nleg = \"middle\"\njoint = \"fti\"\n"
      "[simulation]\nintegrator = \"dopri5\"\nrtol = 1e-4\natol = 1e-4\n"
      "[simulation.expert]\npartitioning = \"neurons\"\nnetwork_tol = 1e-7\n",
      "j.toml");
  auto scenario = config::build_scenario(cfg);
  solver::SolverOptions o = config::simulation_settings(cfg, scenario.get()).solver;
  auto m = config::build_model(cfg);
  o.stiff_part_atol_by_unit = stiff_by_unit;
  return solver::Simulator(*m, o).run(m->parameters().values(), solver::output_grid(2000.0, 5.0));
}

}  // namespace

TEST(StateAtol, LooserPotentialsTakeFewerStepsAndAtolItselfChangesNothing) {
  for (auto partitioning : {solver::Partitioning::Off, solver::Partitioning::On}) {
    const solver::SolveResult scalar = run_leg(partitioning, {});
    const solver::SolveResult same = run_leg(partitioning, {{"mV", 1e-7}});
    const solver::SolveResult loose = run_leg(partitioning, {{"mV", 1e-5}});
    EXPECT_EQ(same.stats.steps, scalar.stats.steps);
    EXPECT_EQ(same.y, scalar.y);
    EXPECT_LT(loose.stats.steps, scalar.stats.steps * 0.95) << "partitioned " << (partitioning == solver::Partitioning::On);
  }
}

// A unit no state has is an error naming it and the model's units, whole system and partitioned
// (the velocities are in rad/s: "rad/ms" once changed nothing without a word).
TEST(StateAtol, AUnitNoStateHasIsAnError) {
  for (auto partitioning : {solver::Partitioning::Off, solver::Partitioning::On}) {
    try {
      run_leg(partitioning, {{"mV", 1e-5}, {"rad/ms", 1e-6}});
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("solver option 'atol_by_unit': no state of this model has unit 'rad/ms'"), std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find("'rad/s'"), std::string::npos) << e.what();
    }
  }
}

// The network part of the neurons partition takes its own atol by unit: stiff_part_tol itself
// as the unit's value reproduces the run bit for bit; a looser one for the potentials takes
// fewer steps (the spiking part keeps rtol, atol); a unit no state has is an error naming the key.
TEST(StateAtol, TheNeuronsPartitionsNetworkPartTakesItsOwn) {
  const solver::SolveResult plain = run_neurons_partition({});
  const solver::SolveResult same = run_neurons_partition({{"mV", 1e-7}, {"1", 1e-7}});
  const solver::SolveResult loose = run_neurons_partition({{"mV", 1e-4}});
  EXPECT_EQ(same.stats.steps, plain.stats.steps);
  EXPECT_EQ(same.y, plain.y);
  EXPECT_LT(loose.stats.steps, plain.stats.steps * 0.95);
  try {
    run_neurons_partition({{"rad/ms", 1e-6}});
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("solver option 'stiff_part_atol_by_unit': no state of this model has unit 'rad/ms'"),
              std::string::npos)
        << e.what();
  }
}

TEST(StateAtol, RefusedWithSensitivities) {
  model::LegOptions l;
  l.motoneuron = model::MotoneuronModel::Rate;
  auto m = model::build_leg_model("middle", l);
  solver::SolverOptions o;
  o.atol_by_unit = {{"mV", 1e-5}};
  EXPECT_THROW(solver::Simulator(*m, o).run(m->parameters().values(), solver::output_grid(10.0, 5.0), {}, {0}), Error);
}

TEST(StateAtol, ConfigKey) {
  const std::string head = "[model]\ntype = \"leg\"\nleg = \"middle\"\n[simulation]\n";
  const auto settings = [](const std::string& text, const char* name) {
    const config::Config cfg = config::parse_config(text, name);
    auto scenario = config::build_scenario(cfg);
    return config::simulation_settings(cfg, scenario.get());
  };
  const std::string expert = "[simulation.expert]\npartitioning = \"joints\"\n";
  const auto s = settings(head + expert + "atol_by_unit = { mV = 1e-5, \"1\" = 1e-6 }\n", "a.toml").solver;
  ASSERT_EQ(s.atol_by_unit.size(), 2u);
  double mv = 0, one = 0;
  for (const auto& [u, v] : s.atol_by_unit) (u == "mV" ? mv : one) = v;
  EXPECT_EQ(mv, 1e-5);
  EXPECT_EQ(one, 1e-6);
  EXPECT_THROW(settings(head + expert + "atol_by_unit = { mV = 0 }\n", "b.toml"), Error);
  EXPECT_THROW(settings(head + expert + "atol_by_unit = 1e-5\n", "c.toml"), Error);
  EXPECT_THROW(settings(head + expert + "threads = 0\n", "d.toml"), Error);
  const std::string neurons = "integrator = \"dopri5\"\n[simulation.expert]\npartitioning = \"neurons\"\n";
  const auto t = settings(head + neurons + "network_atol_by_unit = { mV = 1e-4 }\n", "e.toml");
  ASSERT_EQ(t.solver.stiff_part_atol_by_unit.size(), 1u);
  EXPECT_EQ(t.solver.stiff_part_atol_by_unit[0], (std::pair<std::string, double>("mV", 1e-4)));
  EXPECT_TRUE(t.solver.atol_by_unit.empty());
  try {
    settings(head + neurons + "network_atol_by_unit = { mV = -1 }\n", "f.toml");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("f.toml:8"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'network_atol_by_unit' tolerances must be > 0"), std::string::npos) << e.what();
  }
  // Without the neurons partition, or with BDF everywhere, it would change nothing: refused,
  // naming the file, the [simulation] table's line and the option.
  for (const std::string& other : {std::string("integrator = \"dopri5\"\n[simulation.expert]\npartitioning = \"joints\"\n"),
                                   std::string("integrator = \"cvodes_bdf\"\n[simulation.expert]\npartitioning = \"neurons\"\n")}) {
    try {
      settings(head + other + "network_atol_by_unit = { mV = 1e-4 }\n", "g.toml");
      ADD_FAILURE() << "no error for " << other;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("g.toml:4: [simulation]: expert.network_atol_by_unit applies only with "
                                           "partitioning = \"neurons\""),
                std::string::npos)
          << e.what();
    }
  }
}
