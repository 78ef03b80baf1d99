// The automatic-differentiation Jacobian of the templated right-hand side against central
// finite differences, for the mechanical joint and the full single-joint network.
#include <gtest/gtest.h>

#include <cmath>

#include "model/mechanical_joint_model.hpp"
#include "model/network_builder.hpp"
#include "solver/simulator.hpp"

using namespace phasmid;

static void expect_jacobian_matches_fd(const model::OdeModel& m, const std::vector<double>& y, double t) {
  auto p = m.parameters().values();
  const size_t n = m.num_states();
  auto J = solver::jacobian_autodiff(m, t, y, p);
  std::vector<double> fp(n), fm(n);
  for (size_t j = 0; j < n; ++j) {
    double h = 1e-6 * std::max(1.0, std::abs(y[j]));
    auto yp = y, ym = y;
    yp[j] += h;
    ym[j] -= h;
    m.rhs(t, yp.data(), p.data(), fp.data());
    m.rhs(t, ym.data(), p.data(), fm.data());
    for (size_t i = 0; i < n; ++i) {
      double fd = (fp[i] - fm[i]) / (2 * h);
      double ad = J[j * n + i];
      EXPECT_NEAR(ad, fd, 1e-5 * std::max(1.0, std::abs(fd)))
          << m.states()[i].name << " wrt " << m.states()[j].name;
    }
  }
}

TEST(Jacobian, MechanicalFtiMatchesFiniteDifferences) {
  model::MechanicalJointModel m("middle", model::JointType::Fti, true, 250, 500, 45);
  expect_jacobian_matches_fd(m, {70 * M_PI / 180, 3.0}, 100.0);
  expect_jacobian_matches_fd(m, {70 * M_PI / 180, -3.0}, 300.0);
}

TEST(Jacobian, SingleJointNetworkMatchesFiniteDifferences) {
  auto m = model::build_single_joint_model("middle", model::JointType::Fti);
  // A state along a real trajectory (mid-burst), not the initial guess.
  solver::Simulator sim(*m);
  auto r = sim.run(m->parameters().values(), {0.0, 1234.0});
  std::vector<double> y(r.y.begin() + m->num_states(), r.y.end());
  expect_jacobian_matches_fd(*m, y, 1234.0);
}

TEST(Jacobian, RateMotoneuronNetworkMatchesFiniteDifferences) {
  // The rate formulation (docs/model.md): rate MN states and the rate-driven activation.
  auto m = model::build_single_joint_model("middle", model::JointType::Fti, "", model::MotoneuronModel::Rate);
  solver::Simulator sim(*m);
  // 1234 ms: the flexor MN is firing (R ~ 1); 1500 ms: during the switch.
  for (double t : {1234.0, 1500.0}) {
    auto r = sim.run(m->parameters().values(), {0.0, t});
    std::vector<double> y(r.y.begin() + m->num_states(), r.y.end());
    expect_jacobian_matches_fd(*m, y, t);
  }
}
