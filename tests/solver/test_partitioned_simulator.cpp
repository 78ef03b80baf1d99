// Partitioned integration (solver/partitioned_simulator.hpp): one CVODES integrator per joint
// network, the joints reading each other's angles from interpolating polynomials.
//  - The partition is exact: each part's equations, given only its own states and its inputs
//    (every other entry NaN), reproduce the whole model's right-hand side bit for bit.
//  - The integration converges to the same solution as the whole system's: against a tight
//    reference, its event times are about as accurate as the whole system's at the same
//    tolerance, and they converge with the tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>

#include "features/features.hpp"
#include "model/leg_network.hpp"
#include "model/network_builder.hpp"
#include "common/error.hpp"
#include "solver/simulator.hpp"

using namespace phasmid;

namespace {

// Every part's equations against the whole right-hand side at states along a trajectory
// (so that sigmoids are in their switching range) and randomly perturbed ones.
// Joints: inputs are joint angles only. Neurons: also neurons' potentials.
void expect_parts_reproduce_rhs(const model::OdeModel& m, double t_end,
                                model::PartitionGrain grain = model::PartitionGrain::Joints) {
  const model::ModelPartition P = m.partition(grain);
  ASSERT_GE(P.size(), 2u);
  const size_t n = m.num_states();
  std::vector<int> owner(n, -1);
  for (size_t k = 0; k < P.size(); ++k)
    for (size_t i : P.states[k]) {
      EXPECT_EQ(owner[i], -1) << m.states()[i].name << " in two parts";
      owner[i] = static_cast<int>(k);
    }
  for (size_t i = 0; i < n; ++i) EXPECT_GE(owner[i], 0) << m.states()[i].name << " in no part";
  // Inputs are joint angles of other parts (the slow couplings the scheme interpolates), with
  // the Neurons grain also presynaptic potentials.
  const auto& neurons = m.structure().neurons;
  for (size_t k = 0; k < P.size(); ++k)
    for (size_t i : P.inputs[k]) {
      EXPECT_NE(owner[i], static_cast<int>(k));
      const bool angle = std::any_of(m.angles().begin(), m.angles().end(), [&](const auto& a) { return a.angle_state == i; });
      const bool potential = grain == model::PartitionGrain::Neurons &&
                             std::any_of(neurons.begin(), neurons.end(), [&](const auto& nr) { return nr.v_state == i; });
      EXPECT_TRUE(angle || potential) << P.names[k] << " reads " << m.states()[i].name;
    }

  const auto p = m.parameters().values();
  solver::SolverOptions o;
  o.rtol = o.atol = 1e-6;
  o.partitioning = solver::Partitioning::Off;
  const auto grid = solver::output_grid(t_end, t_end / 20);
  const solver::SolveResult r = solver::Simulator(m, o).run(p, grid);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.05);
  std::vector<double> f_whole(n), y_part(n), f_part(n);
  for (size_t k_out = 0; k_out < grid.size(); ++k_out) {
    std::vector<double> y(r.y.begin() + static_cast<long>(k_out * n), r.y.begin() + static_cast<long>((k_out + 1) * n));
    if (k_out % 2) for (double& v : y) v *= 1.0 + noise(rng);
    m.rhs(grid[k_out], y.data(), p.data(), f_whole.data());
    for (size_t k = 0; k < P.size(); ++k) {
      auto eq = m.make_part(P, k);
      std::fill(y_part.begin(), y_part.end(), NAN);
      std::fill(f_part.begin(), f_part.end(), NAN);
      for (size_t i : P.states[k]) y_part[i] = y[i];
      for (size_t i : P.inputs[k]) y_part[i] = y[i];
      eq->rhs(grid[k_out], y_part.data(), p.data(), f_part.data());
      // Joints: bit for bit. Neurons: a part's batch of exponentials (model/exp_batch.hpp) puts
      // an argument in another lane or the scalar tail, which round differently in the last bit.
      const double ulps = grain == model::PartitionGrain::Joints ? 0.0 : 1e-13;
      for (size_t i : P.states[k])
        ASSERT_NEAR(f_part[i], f_whole[i], ulps * std::abs(f_whole[i])) << P.names[k] << ": " << m.states()[i].name;
      // Bound to p (OdeModelPart::bind, as the driver does): the same numbers.
      std::vector<double> f_bound(n, NAN);
      eq->bind(p.data());
      eq->rhs(grid[k_out], y_part.data(), p.data(), f_bound.data());
      for (size_t i : P.states[k]) ASSERT_EQ(f_bound[i], f_part[i]) << "bound " << P.names[k] << ": " << m.states()[i].name;
    }
  }
}

struct EventTimes {
  std::vector<double> t;
  std::vector<size_t> root;
};
EventTimes events(const model::OdeModel& m, double t_end, double rtol, bool partitioned, int threads = 1) {
  solver::SolverOptions o;
  o.rtol = o.atol = rtol;
  o.partitioning = partitioned ? solver::Partitioning::On : solver::Partitioning::Off;
  o.threads = threads;
  const auto r = solver::Simulator(m, o).run(m.parameters().values(), solver::output_grid(t_end, 5.0),
                                             features::feature_roots(m));
  EventTimes e;
  for (const auto& ev : r.events) {
    e.t.push_back(ev.t);
    e.root.push_back(ev.root);
    for (double v : ev.y) EXPECT_TRUE(std::isfinite(v)) << "event state incomplete at " << ev.t;
  }
  for (double v : r.y) EXPECT_TRUE(std::isfinite(v)) << "output incomplete";
  return e;
}
// Largest difference of corresponding events: the k-th crossing of each root in both runs
// (events of different roots close in time may come in either order).
double max_time_error(const EventTimes& a, const EventTimes& ref) {
  double d = 0.0;
  size_t max_root = 0;
  for (size_t r : ref.root) max_root = std::max(max_root, r);
  for (size_t r = 0; r <= max_root; ++r) {
    std::vector<double> ta, tr;
    for (size_t i = 0; i < a.t.size(); ++i) if (a.root[i] == r) ta.push_back(a.t[i]);
    for (size_t i = 0; i < ref.t.size(); ++i) if (ref.root[i] == r) tr.push_back(ref.t[i]);
    EXPECT_EQ(ta.size(), tr.size()) << "crossings of root " << r;
    for (size_t i = 0; i < std::min(ta.size(), tr.size()); ++i) {
      d = std::max(d, std::abs(ta[i] - tr[i]));
    }
  }
  return d;
}

// At rtol (1e-8) every event within 0.02 ms of the whole system's at 1e-10 (0.2 ms is 1/2500 of a
// step period); at the configs' 1e-6 (compare_1e6) no worse than 4x the whole system's error
// at 1e-6 (measured: 0.4x on the rate leg, 1.9x on the rate three legs). threads >= 2: the
// windowed partitioned run (SolverOptions::threads).
void expect_converges_like_whole(const model::OdeModel& m, double t_end, bool compare_1e6, int threads = 1,
                                 double rtol = 1e-8) {
  const EventTimes ref = events(m, t_end, 1e-10, false);
  EXPECT_GT(ref.t.size(), 50u);
  const double parts8 = max_time_error(events(m, t_end, rtol, true, threads), ref);
  std::printf("%s, %d thread(s): %zu events; max |dt| vs whole 1e-10: parts %g %.3g ms", m.kind().c_str(), threads,
              ref.t.size(), rtol, parts8);
  EXPECT_LT(parts8, 0.02);
  if (compare_1e6) {
    const double whole6 = max_time_error(events(m, t_end, 1e-6, false), ref);
    const double parts6 = max_time_error(events(m, t_end, 1e-6, true, threads), ref);
    std::printf(", parts 1e-6 %.3g ms, whole 1e-6 %.3g ms", parts6, whole6);
    EXPECT_LT(parts6, 4 * whole6);
  }
  std::printf("\n");
}

}  // namespace

TEST(PartitionedSimulator, PartsReproduceTheWholeRightHandSide) {
  model::ThreeLegOptions t;
  expect_parts_reproduce_rhs(*model::build_three_leg_model(t), 1500.0);
  t.motoneuron = model::MotoneuronModel::Rate;
  expect_parts_reproduce_rhs(*model::build_three_leg_model(t), 1500.0);
  model::LegOptions l;
  l.thc_set = "A.17";
  l.direction_switch = true;
  l.ld_release_ms = 150.0;
  expect_parts_reproduce_rhs(*model::build_leg_model("middle", l), 1500.0);
}

// The Neurons grain: each joint's CPG and interneurons (stiff, no spikes) apart from its
// motoneurons, muscles and mechanics, which read the interneurons' potentials.
TEST(PartitionedSimulator, NeuronsGrainSplitsTheSpikingCellsFromTheirNetwork) {
  auto joint = model::build_single_joint_model("middle", model::JointType::Fti);
  const model::ModelPartition P = joint->partition(model::PartitionGrain::Neurons);
  ASSERT_EQ(P.size(), 2u);
  ASSERT_EQ(P.stiff.size(), 2u);
  EXPECT_EQ(P.states[0].size(), 12u);  // 2 CPG, 2 inhibitory and 2 sensory interneurons, (V, h) each
  EXPECT_TRUE(P.stiff[0]);
  EXPECT_EQ(P.states[1].size(), 14u);  // 2 motoneurons (5 states), 2 muscles, angle, velocity
  EXPECT_FALSE(P.stiff[1]);
  EXPECT_EQ(P.names[1], "middle.fti");
  std::vector<std::string> read;
  for (size_t i : P.inputs[1]) read.push_back(joint->states()[i].name);
  EXPECT_EQ(read, (std::vector<std::string>{"middle.fti.in_flx.V", "middle.fti.in_ext.V"}));
  EXPECT_TRUE(P.inputs[0].empty());  // the isolated joint has no sensory feedback
  expect_parts_reproduce_rhs(*joint, 1500.0, model::PartitionGrain::Neurons);

  model::ThreeLegOptions t;
  auto legs = model::build_three_leg_model(t);
  const model::ModelPartition L = legs->partition(model::PartitionGrain::Neurons);
  EXPECT_EQ(L.size(), 18u);
  EXPECT_EQ(std::count(L.stiff.begin(), L.stiff.end(), 1), 9);
  expect_parts_reproduce_rhs(*legs, 1500.0, model::PartitionGrain::Neurons);
  // Rate motoneurons: no spikes to split off, the Joints partition.
  t.motoneuron = model::MotoneuronModel::Rate;
  auto rate = model::build_three_leg_model(t);
  EXPECT_EQ(rate->partition(model::PartitionGrain::Neurons).size(), 9u);
  EXPECT_TRUE(rate->partition(model::PartitionGrain::Neurons).stiff.empty());
}

// A part bound to a parameter vector follows it when bound again after its values change
// (a triggered command time), and reads the values it is passed when called with another one.
// So does the whole model as one part (OdeModel::make_whole, the whole-system driver's).
TEST(PartitionedSimulator, BoundPartsFollowTheirParameters) {
  model::ThreeLegOptions t;
  for (auto mn : {model::MotoneuronModel::Spiking, model::MotoneuronModel::Rate}) {
    t.motoneuron = mn;
    auto m = model::build_three_leg_model(t);
    const model::ModelPartition P = m->partition(model::PartitionGrain::Joints);
    const size_t n = m->num_states();
    std::vector<double> p = m->parameters().values();
    const std::vector<double> y = m->initial_state(p);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> factor(0.99, 1.01);
    std::vector<std::unique_ptr<model::OdeModelPart>> parts;
    std::vector<std::vector<size_t>> states = P.states;
    for (size_t k = 0; k < P.size(); ++k) parts.push_back(m->make_part(P, k));
    parts.push_back(m->make_whole());
    ASSERT_TRUE(parts.back());
    states.emplace_back(n);
    for (size_t i = 0; i < n; ++i) states.back()[i] = i;
    for (auto& part : parts) part->bind(p.data());
    std::vector<double> f_whole(n), f_part(n);
    auto expect_whole = [&](const std::vector<double>& q, const char* what) {
      m->rhs(0.0, y.data(), q.data(), f_whole.data());
      for (size_t k = 0; k < parts.size(); ++k) {
        parts[k]->rhs(0.0, y.data(), q.data(), f_part.data());
        for (size_t i : states[k]) ASSERT_EQ(f_part[i], f_whole[i]) << what << ": " << m->states()[i].name;
      }
    };
    expect_whole(p, "bound");
    for (double& v : p) v *= factor(rng);
    for (auto& part : parts) part->bind(p.data());
    expect_whole(p, "bound again after a change");
    std::vector<double> other = p;
    for (double& v : other) v *= factor(rng);
    expect_whole(other, "called with another vector");
  }
}

TEST(PartitionedSimulator, ThreeLegsAreNineJointParts) {
  model::ThreeLegOptions t;
  t.motoneuron = model::MotoneuronModel::Rate;
  auto m = model::build_three_leg_model(t);
  const model::ModelPartition P = m->partition(model::PartitionGrain::Joints);
  ASSERT_EQ(P.size(), 9u);
  for (const char* leg : {"front", "middle", "hind"})
    for (const char* joint : {"thc", "ctr", "fti"})
      EXPECT_NE(std::find(P.names.begin(), P.names.end(), std::string(leg) + "." + joint), P.names.end());
}

TEST(PartitionedSimulator, EventTimesConvergeLikeTheWholeSystem) {
  model::LegOptions l;
  l.thc_set = "A.17";
  l.motoneuron = model::MotoneuronModel::Rate;
  expect_converges_like_whole(*model::build_leg_model("middle", l), 3000.0, true);
  model::ThreeLegOptions t;
  t.motoneuron = model::MotoneuronModel::Rate;
  expect_converges_like_whole(*model::build_three_leg_model(t), 3000.0, true);
  // Spiking: at 1e-6 the partitioned run steps over a pair of FTi velocity zeros 0.3 ms apart
  // (a wiggle at 999.4 ms that the whole system's smaller steps resolve), so no 1e-6 check. At
  // rtol near 1e-8 the spike-timed events scatter, in the whole system as in the parts: the
  // largest error over rtol 0.5, 0.8, 1, 1.25, 2 x 1e-8 was 0.005-0.028 ms for the whole system
  // and 0.015-0.055 ms for the parts, which a change of rounding moves within that range; at
  // 0.5-2 x 1e-9 the parts' is 0.0018-0.0034 ms. So the bound is asserted at 1e-9.
  l.motoneuron = model::MotoneuronModel::Spiking;
  expect_converges_like_whole(*model::build_leg_model("middle", l), 3000.0, false, 1, 1e-9);
}

// Central commands are synchronisation points: all parts restart there together. The middle
// leg switched to backward walking at 1500 ms (a breakpoint) converges as well.
// The windowed run (two threads, snapshots of the other parts' angles over 0.25 ms windows)
// meets the same bounds: the leg and three legs with rate motoneurons, the spiking leg at 1e-9.
TEST(PartitionedSimulator, WindowedRunConvergesLikeTheWholeSystem) {
  model::LegOptions l;
  l.thc_set = "A.17";
  l.motoneuron = model::MotoneuronModel::Rate;
  expect_converges_like_whole(*model::build_leg_model("middle", l), 3000.0, true, 2);
  model::ThreeLegOptions t;
  t.motoneuron = model::MotoneuronModel::Rate;
  expect_converges_like_whole(*model::build_three_leg_model(t), 3000.0, true, 2);
  l.motoneuron = model::MotoneuronModel::Spiking;
  expect_converges_like_whole(*model::build_leg_model("middle", l), 3000.0, false, 2, 1e-9);
}

TEST(PartitionedSimulator, ConvergesAcrossCentralCommands) {
  model::LegOptions l;
  l.thc_set = "A.17";
  l.direction_switch = true;
  l.motoneuron = model::MotoneuronModel::Rate;
  auto m = model::build_leg_model("middle", l);
  m->parameters().set("middle.command.backward_ms", 1500.0);
  ASSERT_EQ(m->breakpoints(m->parameters().values(), 3000.0).size(), 2u);  // CS on at 200 ms, backward
  expect_converges_like_whole(*m, 3000.0, true);
}

// A run that needs more steps than SolverOptions::max_steps between two outputs fails with a
// message naming the part, as the whole-system integrator does (CV_ONE_STEP would not).
// Also on two threads, where the part that fails may be one stepping ahead of the window: the
// other threads stop and the run reports it (no thread waits for the failed part).
TEST(PartitionedSimulator, StepLimitNamesThePart) {
  model::ThreeLegOptions t;
  t.motoneuron = model::MotoneuronModel::Rate;
  auto m = model::build_three_leg_model(t);
  for (int threads : {1, 2}) {
    solver::SolverOptions o;
    o.rtol = o.atol = 1e-6;
    o.max_steps = 20;
    o.partitioning = solver::Partitioning::On;
    o.threads = threads;
    try {
      solver::Simulator(*m, o).run(m->parameters().values(), solver::output_grid(500.0, 250.0));
      FAIL() << "expected a SolverError, threads = " << threads;
    } catch (const SolverError& e) {
      EXPECT_NE(std::string(e.what()).find("CV_TOO_MUCH_WORK"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(" in part "), std::string::npos) << e.what();
    }
  }
}
