// SolverOptions::validate (solver/solver_options.hpp): the defaults are valid; every field out
// of its range and every contradictory combination is refused with a one-line message naming
// the option and its limit (never a config section); Simulator's constructor applies it.
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "model/network_builder.hpp"
#include "solver/simulator.hpp"

using namespace phasmid;

namespace {

// is_valid's message for the options changed by `change` ("" when valid).
std::string message(const std::function<void(solver::SolverOptions&)>& change) {
  solver::SolverOptions o;
  change(o);
  std::string error;
  const bool valid = o.is_valid(&error);
  EXPECT_EQ(valid, error.empty()) << error;
  return error;
}

}  // namespace

TEST(SolverOptions, DefaultsAreValid) {
  const solver::SolverOptions o;
  EXPECT_TRUE(o.is_valid(nullptr));
  EXPECT_NO_THROW(o.validate());
}

TEST(SolverOptions, EachRangeIsCheckedAndNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    std::function<void(solver::SolverOptions&)> change;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {[](auto& o) { o.rtol = 2; }, "solver option 'rtol' must be in (0, 1), got 2"},
      {[](auto& o) { o.rtol = 0; }, "solver option 'rtol' must be in (0, 1), got 0"},
      {[&](auto& o) { o.rtol = nan; }, "solver option 'rtol' must be in (0, 1), got nan"},
      {[](auto& o) { o.atol = -1e-6; }, "solver option 'atol' must be in (0, 1), got -1e-06"},
      {[](auto& o) { o.atol = 1; }, "solver option 'atol' must be in (0, 1), got 1"},
      {[](auto& o) { o.max_steps = 0; }, "solver option 'max_steps' must be >= 1, got 0"},
      {[](auto& o) { o.max_step_ms = -1; }, "solver option 'max_step_ms' must be >= 0 (0: no limit), got -1"},
      {[](auto& o) { o.sensitivity_tolerance_factor = 0; },
       "solver option 'sensitivity_tolerance_factor' must be > 0, got 0"},
      {[](auto& o) { o.stiff_part_tol = 1.5; }, "solver option 'stiff_part_tol' must be in (0, 1), got 1.5"},
      {[](auto& o) { o.threads = 0; }, "solver option 'threads' must be in 1..256, got 0"},
      {[](auto& o) { o.threads = 257; }, "solver option 'threads' must be in 1..256, got 257"},
      {[](auto& o) { o.window_ms = 0; }, "solver option 'window_ms' must be > 0, got 0"},
      {[](auto& o) { o.atol_by_unit = {{"mV", 0.0}}; },
       "solver option 'atol_by_unit' must be a list of tolerances in (0, 1), got 0 for unit 'mV'"},
      {[](auto& o) { o.atol_by_unit = {{"mV", 1e-5}, {"mV", 1e-4}}; },
       "solver option 'atol_by_unit' names unit 'mV' twice"},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(message(c.change), c.expected);
    solver::SolverOptions o;
    c.change(o);
    try {
      o.validate();
      ADD_FAILURE() << "no error for " << c.expected;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), c.expected);
    }
  }
  // The limits themselves.
  EXPECT_EQ(message([](auto& o) { o.threads = 256; }), "");
  EXPECT_EQ(message([](auto& o) { o.max_step_ms = 0; }), "");
  EXPECT_EQ(message([](auto& o) { o.rtol = o.atol = 1e-13; }), "");
}

TEST(SolverOptions, CombinationsThatWouldChangeNothingOrCannotRunAreRefused) {
  const std::string neurons_threads = message([](auto& o) {
    o.partitioning = solver::Partitioning::Neurons;
    o.threads = 2;
  });
  EXPECT_NE(neurons_threads.find("solver option 'partitioning' = neurons runs on one thread (threads = 1, got 2)"),
            std::string::npos)
      << neurons_threads;
  EXPECT_NE(neurons_threads.find(solver::kNeuronsOnOneThread), std::string::npos);
  EXPECT_EQ(message([](auto& o) {
              o.partitioning = solver::Partitioning::On;
              o.threads = 2;
            }),
            "");

  const std::string applies = "solver option 'stiff_part_atol_by_unit' applies only with partitioning = neurons";
  for (auto partitioning : {solver::Partitioning::On, solver::Partitioning::Off})
    EXPECT_EQ(message([&](auto& o) {
                o.integrator = solver::IntegratorKind::Dopri5;
                o.partitioning = partitioning;
                o.stiff_part_atol_by_unit = {{"mV", 1e-4}};
              }).find(applies),
              0u);
  EXPECT_EQ(message([](auto& o) {  // BDF everywhere: the network parts already run at stiff_part_tol
              o.partitioning = solver::Partitioning::Neurons;
              o.stiff_part_atol_by_unit = {{"mV", 1e-4}};
            }).find(applies),
            0u);
  EXPECT_EQ(message([](auto& o) {
              o.integrator = solver::IntegratorKind::Dopri5;
              o.partitioning = solver::Partitioning::Neurons;
              o.stiff_part_atol_by_unit = {{"mV", 1e-4}};
            }),
            "");
  EXPECT_NE(message([](auto& o) {
              o.integrator = solver::IntegratorKind::Dopri5;
              o.partitioning = solver::Partitioning::Neurons;
              o.stiff_part_atol_by_unit = {{"mV", 2.0}};
            }).find("solver option 'stiff_part_atol_by_unit' must be a list of tolerances in (0, 1), got 2"),
            std::string::npos);
}

TEST(SolverOptions, SimulatorRefusesInvalidOptions) {
  auto joint = model::build_single_joint_model("middle", model::JointType::Fti);
  solver::SolverOptions o;
  o.rtol = 2;
  try {
    solver::Simulator sim(*joint, o);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "solver option 'rtol' must be in (0, 1), got 2");
  }
}
