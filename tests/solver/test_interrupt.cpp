// The process-wide interrupt request (solver/interrupt.hpp): a run in progress stops at its
// next step with solver::Interrupted, both drivers, and runs again once the request is cleared.
#include <gtest/gtest.h>

#include <string>

#include "config/config.hpp"
#include "solver/interrupt.hpp"

namespace phasmid {
namespace {

// Returns the number of integrators of the run after the request was cleared.
long expect_interrupted_then_runs(const config::Config& cfg, solver::Partitioning partitioning) {
  auto s = config::build_scenario(cfg);
  scenario::RunSettings rs = config::simulation_settings(cfg, s.get());
  rs.t_end_ms = 200.0;
  rs.solver.partitioning = partitioning;
  if (partitioning != solver::Partitioning::Neurons) rs.solver.stiff_part_atol_by_unit.clear();  // neurons only (validate)
  solver::request_interrupt();
  try {
    s->run(s->parameters().values(), rs);
    ADD_FAILURE() << "the run did not stop";
  } catch (const solver::Interrupted& e) {
    // Stopped at the first step: its time is the first advance, far before the end.
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("interrupted at t = ", 0), 0u) << m;
    if (m.size() > 19) EXPECT_LT(std::stod(m.substr(19)), 10.0) << m;
  }
  solver::clear_interrupt();
  EXPECT_FALSE(solver::interrupt_requested());
  auto run = s->run(s->parameters().values(), rs);
  EXPECT_NE(run->solution(), nullptr);
  if (!run->solution()) return 0;
  EXPECT_EQ(run->solution()->t.size(), 201u);
  EXPECT_EQ(run->solution()->t.back(), 200.0);
  return run->solution()->stats.integrators;
}

TEST(Interrupt, StopsAWholeSystemRunAtItsFirstStep) {
  EXPECT_EQ(expect_interrupted_then_runs(config::load_config("configs/single_joint_fti.toml"), solver::Partitioning::Off), 1);
}

TEST(Interrupt, StopsAPartitionedRunAtItsFirstStep) {
  // A leg with rate motoneurons: one integrator per joint.
  const config::Config leg = config::parse_config(
      "[model]\ntype = \"leg\"\nleg = \"middle\"\nmotoneuron = \"rate\"\n", "test_interrupt");
  EXPECT_GT(expect_interrupted_then_runs(leg, solver::Partitioning::On), 1);
}

TEST(Interrupt, IsNotASolverErrorSoSweepsDoNotRecordIt) {
  const solver::Interrupted e("x");
  EXPECT_EQ(dynamic_cast<const SolverError*>(static_cast<const Error*>(&e)), nullptr);
}

}  // namespace
}  // namespace phasmid
