// Monodromy matrix and Floquet multipliers of the middle leg's walking cycle
// (configs/middle_leg_forward.toml, 78 states: PR, LD and FE networks with spiking
// motoneurons): sensitivities with respect to all 78 initial states over one period (batched
// Jet<8> right-hand sides, KLU). The monodromy is checked by the flow identity
// Phi(T) f(y0) = f(y(T)), and exactly one multiplier is 1 (the phase direction, eigenvector
// along f(y0)). Stability is not asserted: the orbit does not close (the FE joint keeps its
// own 512 ms rhythm against LD's 506 ms, docs/walking_model.md), see docs/sensitivity.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "config/config.hpp"
#include "sensitivity/floquet.hpp"

using namespace phasmid;

TEST(LegFloquet, MiddleLegMonodromyHasOneTrivialMultiplier) {
  auto cfg = config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/middle_leg_forward.toml");
  auto m = config::build_model(cfg);
  ASSERT_EQ(m->num_states(), 78u);
  sensitivity::FloquetOptions o;
  // Poincare section: the levator CPG neuron depolarising (its voltage rising through -25 mV,
  // once per step). The default section (maxima of the first joint angle) is unusable here:
  // alpha_dot and beta_dot cross zero several times per step during motoneuron bursts.
  o.section = {m->state_index("middle.ctr.cpg_lev.V"), -25.0, +1};
  o.transient_ms = 3000;
  o.max_period_ms = 700;
  o.solver.rtol = o.solver.atol = 1e-8;
  // Without sensitivity error control: 34 000 instead of 92 000 steps (half the CPU time);
  // the monodromy stays accurate to the flow identity's 4e-4 (6e-6 with it, docs).
  o.solver.sensitivity_error_control = false;
  const auto p = m->parameters().values();
  auto r = sensitivity::floquet_analysis(*m, p, o);
  std::printf("period %.3f ms, closure %.3g, trivial multiplier error %.3g, flow identity %.3g, %ld steps\n",
              r.orbit.period_ms, r.closure_error, r.trivial_multiplier_error, r.flow_identity_error,
              r.monodromy_stats.steps);
  for (size_t k = 0; k < 8; ++k) std::printf("  |mu_%zu| = %.6f\n", k, std::abs(r.multipliers[k]));
  EXPECT_NEAR(r.orbit.period_ms, 506.17, 0.5);
  EXPECT_LT(r.flow_identity_error, 2e-3);  // measured 4.0e-4
  EXPECT_LT(r.trivial_multiplier_error, 2e-3);  // measured 3.2e-4
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
