// Knops 2013 Section 3.2.3 (Figs. 3.13-3.14): curve walking with two middle legs; the inner
// leg switching to backward stepping turns the body more than switching to sideward stepping.
// Body kinematics: docs/walking_model.md (model/body_kinematics.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "config/config.hpp"
#include "features/features.hpp"
#include "model/body_kinematics.hpp"

using namespace phasmid;

TEST(CurveWalking, BodyPathKinematics) {
  // Synthetic strides: alpha sweeps 60 -> 120 deg in stance (beta 20 deg), back in swing.
  std::vector<double> t, a, b, a_back;
  for (int k = 0; k <= 1000; ++k) {
    double ph = std::fmod(k / 500.0, 1.0);
    t.push_back(k);
    bool stance = ph < 0.5;
    a.push_back(stance ? 60 + 120 * ph : 120 - 120 * (ph - 0.5));
    a_back.push_back(stance ? 120 - 120 * ph : 60 + 120 * (ph - 0.5));  // protraction in stance
    b.push_back(stance ? 20.0 : 60.0);
  }
  auto straight = model::integrate_body_path(t, a, b, a, b, 38, 15, 2);
  EXPECT_GT(straight.x_mm.back(), 20.0);                   // walks forward
  EXPECT_NEAR(straight.heading_deg.back(), 0.0, 1e-9);     // symmetric: no turn
  EXPECT_NEAR(straight.y_mm.back(), 0.0, 1e-9);
  auto turn = model::integrate_body_path(t, a_back, b, a, b, 38, 15, 2);
  EXPECT_GT(turn.heading_deg.back(), 30.0);                // left leg backward: left turn
  EXPECT_NEAR(turn.x_mm.back(), 0.0, 1e-6);                // on the spot
}

namespace {
double heading_change(const std::vector<std::string>& sets) {
  auto cfg = config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/curve_walking.toml");
  auto m = config::build_model(cfg, sets);
  auto s = config::simulation_settings(cfg);
  solver::Simulator sim(*m, s.solver);
  auto r = sim.run(m->parameters().values(), solver::output_grid(5000, 2.0));
  std::map<std::string, std::vector<double>> ang;
  for (const auto& ch : m->angles()) {
    std::vector<double> x;
    for (size_t k = 0; k < r.t.size(); ++k) x.push_back(r.state(k, ch.angle_state) * 180 / M_PI);
    ang[ch.leg + "." + ch.joint] = x;
  }
  auto p = model::integrate_body_path(r.t, ang["L2.thc"], ang["L2.ctr"], ang["R2.thc"], ang["R2.ctr"],
                                      m->parameters().value("L2.coupling.beta_thr_pr"),
                                      m->parameters().value("body.reach_mm"), m->parameters().value("body.half_width_mm"));
  // Heading change over the turning window 3000-5000 ms.
  size_t k0 = 0;
  while (r.t[k0] < 3000) ++k0;
  return p.heading_deg.back() - p.heading_deg[k0];
}
}  // namespace

TEST(CurveWalking, BackwardSteppingTurnsMoreThanSidewardStepping) {
  double back = heading_change({"L2.command.backward_ms=3000", "L2.command.forward_ms=1e9"});
  double side = heading_change({"L2.command.backward_ms=1e9", "L2.command.forward_ms=1e9", "L2.command.sideward_ms=3000"});
  // Section 3.2.3: "the angle of turning is much larger in the first case". (Forward walking
  // itself drifts to the left in phasmid's kinematic body model, docs/walking_model.md, so
  // the sideward change is not asserted on its own.)
  EXPECT_GT(back, 0.0);  // towards the inner (left) leg
  EXPECT_GT(back, 1.5 * side);
}
