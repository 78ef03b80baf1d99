// Section 3.1.1 / Fig. 3.1: configs/fti_mechanical.toml reproduces the stated time course.
#include <gtest/gtest.h>

#include <cmath>

#include "config/config.hpp"
#include "build_info.hpp"

using namespace phasmid;

namespace {
double gamma_deg_at(const std::vector<std::string>& sets, double t_ms) {
  auto cfg = config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/fti_mechanical.toml");
  auto m = config::build_model(cfg, sets);
  solver::Simulator sim(*m, config::simulation_settings(cfg).solver);
  auto r = sim.run(m->parameters().values(), {0.0, t_ms});
  return r.state(1, 0) * 180.0 / M_PI;
}
std::vector<std::string> scaled(double kE) {
  // Fig. 3.1B-D: k_E varied, k_F = a_FE k_E (a_FE = 296/510)
  return {"middle.fti.k_E.flexion=" + std::to_string(kE), "middle.fti.k_F.flexion=" + std::to_string(kE * 296.0 / 510.0)};
}
}  // namespace

TEST(FtiMechanical, Fig31A_ArrivesNear110At250msAndReturnsNear45At500ms) {
  EXPECT_NEAR(gamma_deg_at({}, 250.0), 110.0, 2.0);
  EXPECT_NEAR(gamma_deg_at({}, 500.0), 45.0, 2.0);
}

TEST(FtiMechanical, Fig31C_LargerSpringConstantsOvershoot) {
  // k_E = 1100: the flexion overshoots gamma_max = 110 deg before the switch.
  auto cfg = config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/fti_mechanical.toml");
  auto m = config::build_model(cfg, scaled(1100));
  solver::Simulator sim(*m);
  auto r = sim.run(m->parameters().values(), solver::output_grid(250, 1));
  double peak = 0;
  for (size_t k = 0; k < r.t.size(); ++k) peak = std::max(peak, r.state(k, 0) * 180 / M_PI);
  EXPECT_GT(peak, 115.0);
}

TEST(FtiMechanical, Fig31D_SmallerSpringConstantsFallShort) {
  // k_E = 250: slower motion, gamma_max is not attained during flexion.
  double g = gamma_deg_at(scaled(250), 250.0);
  EXPECT_LT(g, 109.0);
  EXPECT_GT(g, 90.0);  // still a flexion, not a failure to move
}

TEST(FtiMechanical, ViscositySlowsTheMotion) {
  // "the motion can be made slower by increasing b_v": at 75 ms flexion has progressed less.
  double fast = gamma_deg_at({}, 75.0), slow = gamma_deg_at({"middle.fti.b_v=25"}, 75.0);
  EXPECT_LT(slow, fast - 5.0);
}
