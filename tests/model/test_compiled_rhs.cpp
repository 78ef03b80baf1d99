// Compiled right-hand sides (model/compiled_rhs.hpp, SolverOptions::compiled_rhs): the code a
// network writes for one part returns the generic evaluation's values bit for bit, for every
// component kind (NaP neurons, spiking and rate motoneurons, gated synapses, sensory and
// central modulations, rest-tone releases, muscles, the three joint types); a run with it gives
// the same trajectory; a source that does not compile is reported, not loaded.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>

#include "model/compiled_rhs.hpp"
#include "model/leg_network.hpp"
#include "model/network_builder.hpp"
#include "solver/simulator.hpp"

using namespace phasmid;

namespace {

// A cache of this test process's own, removed at the end.
struct TempCache {
  std::string dir = std::filesystem::temp_directory_path() / ("phasmid-rhs-test-" + std::to_string(getpid()));
  TempCache() { setenv("PHASMID_CACHE_DIR", dir.c_str(), 1); }
  ~TempCache() { std::filesystem::remove_all(dir); }
};

// Every part of partition P (and the whole model) compiled against the same part generic, at
// states along a trajectory (sigmoids in their switching range) and perturbed ones, at times on
// both sides of the central commands.
void expect_compiled_equals_generic(const model::OdeModel& m, model::PartitionGrain grain, double t_end) {
  const auto p = m.parameters().values();
  solver::SolverOptions o;
  o.rtol = o.atol = 1e-6;
  o.partitioning = solver::Partitioning::Off;
  const auto grid = solver::output_grid(t_end, t_end / 10);
  const solver::SolveResult r = solver::Simulator(m, o).run(p, grid);
  const size_t n = m.num_states();
  const model::ModelPartition P = m.partition(grain);
  std::vector<std::unique_ptr<model::OdeModelPart>> generic, compiled;
  for (size_t k = 0; k <= P.size(); ++k) {
    generic.push_back(k < P.size() ? m.make_part(P, k) : m.make_whole());
    compiled.push_back(k < P.size() ? m.make_part(P, k) : m.make_whole());
    std::string why;
    ASSERT_TRUE(compiled.back()->compile(&why)) << why;
  }
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.05);
  std::vector<double> f_generic(n), f_compiled(n);
  for (size_t k_out = 0; k_out < grid.size(); ++k_out) {
    std::vector<double> y(r.y.begin() + static_cast<long>(k_out * n), r.y.begin() + static_cast<long>((k_out + 1) * n));
    if (k_out % 2) for (double& v : y) v *= 1.0 + noise(rng);
    for (size_t k = 0; k <= P.size(); ++k) {
      std::fill(f_generic.begin(), f_generic.end(), NAN);
      std::fill(f_compiled.begin(), f_compiled.end(), NAN);
      generic[k]->rhs(grid[k_out], y.data(), p.data(), f_generic.data());
      compiled[k]->rhs(grid[k_out], y.data(), p.data(), f_compiled.data());
      const std::vector<size_t>& own = k < P.size() ? P.states[k] : std::vector<size_t>{};
      for (size_t i = 0; i < n; ++i) {
        if (k < P.size() && std::find(own.begin(), own.end(), i) == own.end()) continue;
        ASSERT_EQ(f_compiled[i], f_generic[i]) << (k < P.size() ? P.names[k] : "whole") << ": " << m.states()[i].name
                                               << " at t = " << grid[k_out];
      }
      if (k == P.size()) {
        EXPECT_FALSE(compiled[k]->packed());
        continue;
      }
      // The driver's call: own states and inputs packed in the partition's order.
      ASSERT_TRUE(compiled[k]->packed());
      std::vector<double> y_own, u, f_own(own.size(), NAN);
      for (size_t i : own) y_own.push_back(y[i]);
      for (size_t i : P.inputs[k]) u.push_back(y[i]);
      compiled[k]->rhs_packed(grid[k_out], y_own.data(), u.data(), p.data(), f_own.data());
      for (size_t i = 0; i < own.size(); ++i)
        ASSERT_EQ(f_own[i], f_generic[own[i]]) << P.names[k] << " packed: " << m.states()[own[i]].name;
    }
  }
}

}  // namespace

TEST(CompiledRhs, SingleJointBitForBit) {
  TempCache cache;
  auto joint = model::build_single_joint_model("middle", model::JointType::Fti);
  expect_compiled_equals_generic(*joint, model::PartitionGrain::Neurons, 1000.0);
}

// The middle leg with its sensory switches, the ThC set with presynaptic gates and the central
// command's direction switch (time conditions); spiking and rate motoneurons.
TEST(CompiledRhs, LegBitForBit) {
  TempCache cache;
  model::LegOptions l;
  l.thc_set = "A.17";
  l.direction_switch = true;
  l.ld_release_ms = 150.0;
  expect_compiled_equals_generic(*model::build_leg_model("middle", l), model::PartitionGrain::Joints, 1000.0);
  l.motoneuron = model::MotoneuronModel::Rate;
  expect_compiled_equals_generic(*model::build_leg_model("middle", l), model::PartitionGrain::Joints, 1000.0);
}

TEST(CompiledRhs, ThreeLegsBitForBit) {
  TempCache cache;
  model::ThreeLegOptions t;
  t.motoneuron = model::MotoneuronModel::Rate;
  expect_compiled_equals_generic(*model::build_three_leg_model(t), model::PartitionGrain::Joints, 600.0);
}

// The run's own switch: the same trajectory, whole-system and partitioned.
TEST(CompiledRhs, RunsGiveTheSameTrajectory) {
  TempCache cache;
  auto joint = model::build_single_joint_model("middle", model::JointType::Fti);
  const auto p = joint->parameters().values();
  const auto grid = solver::output_grid(1500.0, 1.0);
  for (auto part : {solver::Partitioning::Off, solver::Partitioning::Neurons}) {
    solver::SolverOptions o;
    o.integrator = solver::IntegratorKind::Dopri5;
    o.rtol = o.atol = 1e-6;
    o.partitioning = part;
    const solver::SolveResult generic = solver::Simulator(*joint, o).run(p, grid);
    o.compiled_rhs = true;
    const solver::SolveResult compiled = solver::Simulator(*joint, o).run(p, grid);
    ASSERT_EQ(compiled.y.size(), generic.y.size());
    for (size_t i = 0; i < generic.y.size(); ++i) ASSERT_EQ(compiled.y[i], generic.y[i]) << "entry " << i;
    EXPECT_EQ(compiled.stats.steps, generic.stats.steps);
  }
}

// A source that does not compile: nullptr and the compiler's log named; nothing left loaded.
// A source compiled once is loaded from the cache by a second call.
TEST(CompiledRhs, FailureIsReportedAndObjectsAreCached) {
  TempCache cache;
  std::string why;
  EXPECT_EQ(model::compile_rhs(model::compiled_rhs_preamble() + "this is not C++;\n", "phasmid_rhs", &why), nullptr);
  EXPECT_NE(why.find("the compiler failed"), std::string::npos) << why;
  const std::string log = why.substr(why.find("log ") + 4, why.size() - why.find("log ") - 5);
  EXPECT_TRUE(std::filesystem::exists(log)) << log;

  const std::string src = model::compiled_rhs_preamble() +
                          "extern \"C\" void f(double, const double* y, const double*, const double*, double* ydot, "
                          "const PhasmidRhsContext*)"
                          " { ydot[0] = -2.0 * y[0]; }\n";
  const PhasmidRhsFn f = model::compile_rhs(src, "f", &why);
  ASSERT_NE(f, nullptr) << why;
  double y = 3.0, ydot = 0.0;
  f(0.0, &y, nullptr, nullptr, &ydot, nullptr);
  EXPECT_EQ(ydot, -6.0);
  EXPECT_EQ(model::compile_rhs(src, "f", &why), f);
  size_t objects = 0;
  for (const auto& e : std::filesystem::directory_iterator(cache.dir)) objects += e.path().extension() == ".so";
  EXPECT_EQ(objects, 1u);
}
