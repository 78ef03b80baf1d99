// The IMEX session (solver/ark_imex_session.hpp) and the stiff rates it splits by
// (model/stiff_rates.hpp): the closed form of a stiff forced decay across a restart in far fewer
// steps than the explicit stability bound allows, roots of the harmonic oscillator, and the
// rates against finite-difference diagonals of the single joint's Jacobian.
#include <gtest/gtest.h>

#include <nvector/nvector_serial.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "model/network_builder.hpp"
#include "model/stiff_rates.hpp"
#include "session_checks.hpp"
#include "solver/ark_imex_session.hpp"
#include "solver/cvodes_session.hpp"

using namespace phasmid;

namespace {
// y1' = -k (y1 - c) + a (stiff, kappa = k, offset c), y2' = -0.02 y2 (explicit, kappa = 0).
struct Decay {
  double k = 1000.0, c = -60.0, a = 5.0;
};
int decay_rhs(sunrealtype, N_Vector y, N_Vector ydot, void* ud) {
  const auto* d = static_cast<const Decay*>(ud);
  NV_Ith_S(ydot, 0) = -d->k * (NV_Ith_S(y, 0) - d->c) + d->a;
  NV_Ith_S(ydot, 1) = -0.02 * NV_Ith_S(y, 1);
  return 0;
}
}  // namespace

TEST(ArkImexSession, StiffDecayMatchesTheClosedFormAcrossARestart) {
  for (int order : {4, 5}) {
    solver::SolverOptions so;
    so.rtol = so.atol = 1e-10;
    Decay d;
    auto kappa = [&d](double, const double*, double* k) {
      k[0] = d.k;
      k[1] = 0.0;
    };
    solver::SundialsContext ctx;
    const double y0[2] = {-70.0, 3.0};
    solver::ArkImexSession session(ctx.get(), so, y0, 2, decay_rhs, &d, kappa, {d.c, 0.0}, {order});
    double t = 0.0;
    const long steps_before = test::advance_to_stop_at_50(session, &t);
    // An explicit 4th/5th-order pair needs h < ~3.3 / k: over 15 000 steps for 50 ms.
    std::printf("ARK%d: %ld steps to 50 ms\n", order, steps_before);
    EXPECT_LT(steps_before, 1500) << order;
    d.k = 2000.0;  // the right-hand side switches at 50 ms
    session.restart(t);
    EXPECT_EQ(session.total_steps(), steps_before);
    session.set_stop_time(100.0);
    EXPECT_GE(session.advance(100.0, &t, CV_NORMAL), 0);
    EXPECT_DOUBLE_EQ(t, 100.0);
    EXPECT_NEAR(NV_Ith_S(session.y(), 0), d.c + d.a / d.k, 1e-9) << order;  // relaxed to its equilibrium
    EXPECT_NEAR(NV_Ith_S(session.y(), 1), 3.0 * std::exp(-0.02 * 100.0), 1e-8) << order;
    EXPECT_GT(session.stats().newton_iterations, 0);
    EXPECT_EQ(session.stats().steps, session.total_steps());
  }
}

// y1 = cos t, y2 = -sin t with a stiff-rate split that moves part of the rotation implicit:
// kappa = 0.5 for both states, offset 0.
TEST(ArkImexSession, LocatesRootsInTheirDirection) {
  solver::SolverOptions so;
  so.rtol = so.atol = 1e-10;
  auto kappa = [](double, const double*, double* k) { k[0] = k[1] = 0.5; };
  solver::SundialsContext ctx;
  const double y0[2] = {1.0, 0.0};
  solver::ArkImexSession session(ctx.get(), so, y0, 2, test::oscillator_rhs, nullptr, kappa, {0.0, 0.0});
  session.init_roots({-1, +1}, test::oscillator_roots);
  session.set_stop_time(5.0);
  double t = test::expect_oscillator_roots(session);
  EXPECT_GE(session.advance(5.0, &t, CV_NORMAL), 0);
  EXPECT_NEAR(NV_Ith_S(session.y(), 0), std::cos(5.0), 1e-8);
}

// Motoneuron potentials and gates, and the NaP neurons' h, have equations affine in themselves
// with no other dependence on them: kappa = -df_i/dy_i exactly. A NaP potential's kappa lacks
// the persistent current's m_inf'(V) term, so only its sign is checked there (kappa > 0).
TEST(StiffRates, AreTheSelfRatesOfTheSingleJoint) {
  auto m = model::build_single_joint_model("middle", model::JointType::Fti, "", model::MotoneuronModel::Spiking);
  const std::vector<double> p = m->parameters().values();
  std::vector<double> y = m->initial_state(p);
  y[m->neurons()[0].state] = -40.0;  // a depolarised CPG neuron opens its synapses
  std::vector<double> kappa(y.size()), fp(y.size()), fm(y.size());
  model::stiff_rates(*m, y.data(), p.data(), kappa.data());
  const std::vector<double> c = model::stiff_offsets(*m, p.data());
  size_t checked = 0;
  for (const auto& n : m->neurons()) {
    const size_t states = n.motoneuron ? 4 : 2;
    for (size_t s = 0; s < states; ++s) {
      const size_t i = n.state + s;
      const double h = 1e-6 * std::max(1.0, std::abs(y[i]));
      std::vector<double> yp = y, ym = y;
      yp[i] += h;
      ym[i] -= h;
      m->rhs(0.0, yp.data(), p.data(), fp.data());
      m->rhs(0.0, ym.data(), p.data(), fm.data());
      const double self_rate = -(fp[i] - fm[i]) / (2 * h);
      if (!n.motoneuron && s == 0) {
        EXPECT_GT(kappa[i], 0.0) << n.name;
        EXPECT_EQ(c[i], p[n.nap.E_L]) << n.name;
        continue;
      }
      EXPECT_NEAR(kappa[i], self_rate, 1e-6 * std::abs(self_rate) + 1e-9) << n.name << " state " << s;
      ++checked;
    }
  }
  EXPECT_GE(checked, 8u);  // two motoneurons' four equations at least
  EXPECT_EQ(kappa[m->joints()[0].angle_state], 0.0);
}
