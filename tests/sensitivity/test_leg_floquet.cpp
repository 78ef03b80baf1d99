// Monodromy matrix and Floquet multipliers of the middle leg's walking cycle
// (configs/middle_leg_forward.toml, 78 states: PR, LD and FE networks with spiking
// motoneurons): sensitivities with respect to all 78 initial states over one period (batched
// Jet<8> right-hand sides, KLU). The monodromy is checked by the flow identity
// Phi(T) f(y0) = f(y(T)), and exactly one multiplier is 1 (the phase direction, eigenvector
// along f(y0)). Stability is not asserted for the spiking leg: its orbit does not close spike
// for spike (retractor and extensor MN spikes shift from step to step), and the other
// multipliers above 1 change with tolerance and transient (docs/sensitivity.md). It is
// asserted for the leg with rate motoneurons, whose FE joint is locked 1:1 to LD since
// middle.coupling.g_in12_in11 (docs/walking_model.md, "FE entrainment").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "config/config.hpp"
#include "sensitivity/floquet.hpp"
#include "build_info.hpp"

using namespace phasmid;

namespace {

// Poincare section: the levator CPG neuron depolarising (its voltage rising through -25 mV,
// once per step). The default section (maxima of the first joint angle) is unusable here:
// alpha_dot and beta_dot cross zero several times per step during motoneuron bursts.
// Without sensitivity error control: 34 000 instead of 92 000 steps for the spiking leg (half
// the CPU time); the monodromy stays accurate to the flow identity's 4e-4 (6e-6 with it, docs).
sensitivity::FloquetOptions middle_leg_options(const model::OdeModel& m, double transient_ms) {
  sensitivity::FloquetOptions o;
  o.section = {m.state_index("middle.ctr.cpg_lev.V"), -25.0, +1};
  o.transient_ms = transient_ms;
  o.max_period_ms = 700;
  o.solver.rtol = o.solver.atol = 1e-8;
  o.solver.sensitivity_error_control = false;
  return o;
}

}  // namespace

TEST(LegFloquet, MiddleLegMonodromyHasOneTrivialMultiplier) {
  auto cfg = config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/middle_leg_forward.toml");
  auto m = config::build_model(cfg);
  ASSERT_EQ(m->num_states(), 78u);
  const auto o = middle_leg_options(*m, 3000);
  const auto p = m->parameters().values();
  auto r = sensitivity::floquet_analysis(*m, p, o);
  std::printf("period %.3f ms, closure %.3g, trivial multiplier error %.3g, flow identity %.3g, %ld steps\n",
              r.orbit.period_ms, r.closure_error, r.trivial_multiplier_error, r.flow_identity_error,
              r.monodromy_stats.steps);
  for (size_t k = 0; k < 8; ++k) std::printf("  |mu_%zu| = %.6f\n", k, std::abs(r.multipliers[k]));
  EXPECT_NEAR(r.orbit.period_ms, 506.17, 0.5);
  EXPECT_LT(r.flow_identity_error, 2e-3);  // measured 7.9e-4 (4.0e-4 before the FE entrainment)
  EXPECT_LT(r.trivial_multiplier_error, 2e-3);  // measured 3.6e-4
  int near_one = 0;
  for (auto& mu : r.multipliers) near_one += std::abs(mu - 1.0) < 2e-3;
  EXPECT_EQ(near_one, 1);
  // Its eigenvector is the direction of the flow at the section.
  Eigen::EigenSolver<Eigen::MatrixXd> es(r.monodromy);
  Eigen::Index k1 = 0;
  for (Eigen::Index k = 0; k < es.eigenvalues().size(); ++k)
    if (std::abs(es.eigenvalues()[k] - 1.0) < std::abs(es.eigenvalues()[k1] - 1.0)) k1 = k;
  Eigen::VectorXd v = es.eigenvectors().col(k1).real(), f0(m->num_states());
  m->rhs(r.orbit.t0, r.orbit.y0.data(), p.data(), f0.data());
  EXPECT_GT(std::abs(v.dot(f0)) / (v.norm() * f0.norm()), 0.99);
}

TEST(LegFloquet, RateMotoneuronMiddleLegCycleIsStable) {
  // The middle leg with rate motoneurons (motoneuron = "rate", no spikes) after an 8000 ms
  // transient, rtol 1e-8. Measured with the f-V rate MNs: period 506.171 ms, flow identity
  // 1.1e-3, trivial multiplier 1.00023 (eigenvector: the CTr CPG), then |mu| = 0.99684 (the FE
  // phase: fti.cpg_ext.V, fti.in_flx.V, fti.gamma_dot), 0.639, 0.629, 0.551, 0.514: a stable
  // limit cycle whose FE phase is only weakly entrained (decay 0.3 % per step). With the
  // earlier sigmoid rate MNs the FE mode was not separate (0.774, 0.774, 0.676, ...); before
  // the FE entrainment (middle.coupling.g_in12_in11 = 0.1 nS) it was unstable (1.068).
  auto cfg = config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/middle_leg_forward.toml");
  cfg.table["model"].as_table()->insert_or_assign("motoneuron", "rate");
  auto m = config::build_model(cfg);
  const auto o = middle_leg_options(*m, 8000);
  const auto p = m->parameters().values();
  auto r = sensitivity::floquet_analysis(*m, p, o);
  std::printf("period %.3f ms, closure %.3g, trivial multiplier error %.3g, flow identity %.3g\n", r.orbit.period_ms,
              r.closure_error, r.trivial_multiplier_error, r.flow_identity_error);
  for (size_t k = 0; k < 6; ++k) std::printf("  |mu_%zu| = %.6f\n", k, std::abs(r.multipliers[k]));
  EXPECT_NEAR(r.orbit.period_ms, 506.17, 0.5);
  EXPECT_LT(r.flow_identity_error, 5e-3);
  {
    Eigen::EigenSolver<Eigen::MatrixXd> es(r.monodromy);
    for (Eigen::Index k = 0; k < es.eigenvalues().size(); ++k) {
      double mu = std::abs(es.eigenvalues()[k]);
      if (mu < 0.99) continue;
      Eigen::VectorXd v = es.eigenvectors().col(k).real();
      v /= v.norm();
      std::printf("mode %.6f:", mu);
      std::vector<std::pair<double, size_t>> c;
      for (Eigen::Index i = 0; i < v.size(); ++i) c.push_back({-std::abs(v[i]), (size_t)i});
      std::sort(c.begin(), c.end());
      for (int i = 0; i < 6; ++i) std::printf(" %s %.3f", m->states()[c[i].second].name.c_str(), v[c[i].second]);
      std::printf("\n");
    }
  }
  int trivial = 0;
  for (auto& mu : r.multipliers) {
    if (std::abs(mu - 1.0) < 1e-3) {  // measured 2.3e-4 from 1
      ++trivial;
      continue;
    }
    EXPECT_LT(std::abs(mu), 0.999) << mu;  // measured at most 0.99684 (FE phase), then 0.639
  }
  EXPECT_EQ(trivial, 1);
}
