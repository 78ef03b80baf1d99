// Section 2.4 / Appendix B: the coupled femur-tibia Lagrangian system.
#include <gtest/gtest.h>

#include <cmath>

#include "config/config.hpp"
#include "model/coupled_ctr_fti_model.hpp"
#include "solver/simulator.hpp"
#include "build_info.hpp"

using namespace phasmid;

namespace {
std::vector<double> free_motion_parameters(model::CoupledCtrFtiModel& m) {
  // No muscles, no viscosity: a free double pendulum. A viscosity of 0 is outside what a user
  // may set (docs/model.md "Admissible ranges"), so the values are set by index, unchecked.
  auto& ps = m.parameters();
  for (const char* n : {"middle.ctr.k_L.levation", "middle.ctr.k_D.levation", "middle.ctr.k_L.depression",
                        "middle.ctr.k_D.depression", "middle.fti.k_F.flexion", "middle.fti.k_E.flexion",
                        "middle.fti.k_F.extension", "middle.fti.k_E.extension", "middle.ctr.b_v", "middle.fti.b_v"})
    ps.set(ps.index(n), 0.0);
  return ps.values();
}

// The coupled model started from a moving state (the scenario itself starts at rest).
class Started : public model::OdeModelT<Started> {
 public:
  explicit Started(const model::CoupledCtrFtiModel& base, std::vector<double> y0) : base_(base), y0_(std::move(y0)) {
    params_ = base.parameters();
    states_ = base.states();
  }
  std::string kind() const override { return "started"; }
  std::vector<double> initial_state(const std::vector<double>&) const override { return y0_; }
  template <class T>
  void eval(double t, const T* y, const T* p, T* ydot) const { base_.eval(t, y, p, ydot); }
 private:
  const model::CoupledCtrFtiModel& base_;
  std::vector<double> y0_;
};
}  // namespace

TEST(CoupledCtrFti, FreeMotionConservesKineticEnergy) {
  // Without forces the Lagrangian is T alone (2.58): T must be conserved while beta and gamma
  // exchange momentum through the cos(gamma) coupling.
  model::CoupledCtrFtiModel m;
  auto p = free_motion_parameters(m);
  solver::SolverOptions o;
  o.rtol = o.atol = 1e-11;
  // Start with both joints moving (initial velocities through a short custom start).
  std::vector<double> y0 = {0.5, 2.0, 1.0, -3.0};
  Started started(m, y0);
  auto r = solver::Simulator(started, o).run(p, solver::output_grid(2000, 100));
  double T0 = m.kinetic_energy(y0, p);
  ASSERT_GT(T0, 0.0);
  double max_dev = 0, max_gamma_change = 0;
  for (size_t k = 0; k < r.t.size(); ++k) {
    std::vector<double> y(r.y.begin() + k * 4, r.y.begin() + (k + 1) * 4);
    max_dev = std::max(max_dev, std::abs(m.kinetic_energy(y, p) - T0) / T0);
    max_gamma_change = std::max(max_gamma_change, std::abs(y[3] - y0[3]));
  }
  EXPECT_LT(max_dev, 1e-7);
  EXPECT_GT(max_gamma_change, 0.1);  // the joints really interact (velocities change)
}

TEST(CoupledCtrFti, AppendixB_CouplingChangesTheMotionOnlySlightly) {
  // Appendix B: "the changes in the angular motion with a mechanically coupled system are not
  // dramatic in comparison to the isolated joints". Compare the extremal angles of the coupled
  // run with the isolated FTi (Table A.14) and CTr (Table A.15) mechanical scenarios.
  auto extremes = [](const std::string& cfg_name, size_t state, double& lo, double& hi) {
    auto cfg = config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/" + cfg_name);
    auto m = config::build_model(cfg);
    auto r = solver::Simulator(*m, config::simulation_settings(cfg).solver).run(m->parameters().values(),
                                                                              solver::output_grid(2000, 1));
    lo = 1e9;
    hi = -1e9;
    for (size_t k = 0; k < r.t.size(); ++k) {
      if (r.t[k] < 500) continue;  // second cycle on
      double a = r.state(k, state) * 180 / M_PI;
      lo = std::min(lo, a);
      hi = std::max(hi, a);
    }
  };
  double cb_lo, cb_hi, cg_lo, cg_hi, b_lo, b_hi, g_lo, g_hi;
  extremes("coupled_ctr_fti.toml", 0, cb_lo, cb_hi);
  extremes("coupled_ctr_fti.toml", 2, cg_lo, cg_hi);
  extremes("ctr_mechanical.toml", 0, b_lo, b_hi);
  extremes("fti_mechanical.toml", 0, g_lo, g_hi);
  // Within 10% of each isolated range, but not identical (the coupling acts).
  EXPECT_NEAR(cb_hi - cb_lo, b_hi - b_lo, 0.1 * (b_hi - b_lo));
  EXPECT_NEAR(cg_hi - cg_lo, g_hi - g_lo, 0.1 * (g_hi - g_lo));
  EXPECT_GT(std::abs(cg_hi - g_hi) + std::abs(cg_lo - g_lo) + std::abs(cb_hi - b_hi) + std::abs(cb_lo - b_lo), 0.01);
}
