// Knops 2013 Section 3.2.3 (Figs. 3.13-3.14): curve walking with two middle legs. Forward walking
// goes straight with both legs retracting in stance; the inner leg switching to backward
// stepping turns the body more than switching to sideward stepping.
// Body kinematics: docs/walking_model.md (model/body_kinematics.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "config/config.hpp"
#include "features/features.hpp"
#include "model/body_kinematics.hpp"
#include "build_info.hpp"

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
struct CurveRun {
  std::vector<double> t;
  std::map<std::string, std::vector<double>> ang;  // "<leg>.<joint>" in deg
  model::BodyPath path;
  double beta_thr = 0;
  std::map<std::string, double> release_ms;
};

CurveRun run_curve(const std::vector<std::string>& sets) {
  auto cfg = config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/curve_walking.toml");
  auto m = config::build_model(cfg, sets);
  auto s = config::simulation_settings(cfg);
  solver::Simulator sim(*m, s.solver);
  auto r = sim.run(m->parameters().values(), solver::output_grid(5000, 2.0));
  CurveRun c;
  c.t = r.t;
  for (const auto& ch : m->angles()) {
    std::vector<double> x;
    for (size_t k = 0; k < r.t.size(); ++k) x.push_back(r.state(k, ch.angle_state) * 180 / M_PI);
    c.ang[ch.leg + "." + ch.joint] = x;
  }
  c.beta_thr = m->parameters().value("L2.coupling.beta_thr_pr");
  for (const char* leg : {"L2", "R2"}) c.release_ms[leg] = m->parameters().value(std::string(leg) + ".command.ld_release_ms");
  c.path = model::integrate_body_path(r.t, c.ang["L2.thc"], c.ang["L2.ctr"], c.ang["R2.thc"], c.ang["R2.ctr"], c.beta_thr,
                                      m->parameters().value("body.reach_mm"), m->parameters().value("body.half_width_mm"));
  return c;
}

// Heading change over the turning window 3000-5000 ms.
double heading_change(const CurveRun& c) {
  size_t k0 = 0;
  while (c.t[k0] < 3000) ++k0;
  return c.path.heading_deg.back() - c.path.heading_deg[k0];
}

// Completed stances (beta < threshold for at least 40 ms, as FeatureOptions::min_contact_ms)
// of a leg after its start time: touch-down time and alpha(lift-off) - alpha(touch-down).
std::vector<std::pair<double, double>> stances(const CurveRun& c, const std::string& leg) {
  const auto& a = c.ang.at(leg + ".thc");
  const auto& b = c.ang.at(leg + ".ctr");
  std::vector<std::pair<double, double>> out;
  size_t td = 0;
  bool in = false;
  for (size_t k = 1; k < c.t.size(); ++k) {
    if (!in && b[k] < c.beta_thr && b[k - 1] >= c.beta_thr) {
      in = true;
      td = k;
    } else if (in && b[k] >= c.beta_thr) {
      in = false;
      if (c.t[td] > c.release_ms.at(leg) && c.t[k] - c.t[td] >= 40) out.push_back({c.t[td], a[k] - a[td]});
    }
  }
  return out;
}
}  // namespace

TEST(CurveWalking, ForwardWalkingBothLegsRetractInStanceAndGoStraight) {
  auto c = run_curve({"L2.command.backward_ms=1e9", "L2.command.forward_ms=1e9"});
  // Both (identical) middle legs retract during every stance from their first one on, as the
  // single middle leg (+77 deg, Fig. 3.8). Measured: L2 +64 deg in its first stance (1842 ms),
  // then +75..+78; R2 +76..+78. Without the start-time hold's inhibition of the PR CPGs
  // (--set L2.ld_hold.g_pr=0), L2, released in its free-running PR's protraction phase,
  // changes alpha by -71, +5, +33 deg in its first three stances (docs/walking_model.md,
  // "Curve walking").
  for (const char* leg : {"L2", "R2"}) {
    auto st = stances(c, leg);
    ASSERT_GE(st.size(), 5u) << leg;
    for (const auto& [t_td, da] : st) EXPECT_GT(da, 50.0) << leg << " stance at " << t_td << " ms";
  }
  // Heading at L2's touch-downs (the same phase of the stride: the heading swings by ~25 deg
  // within a stride as the legs push alternately) from 2000 ms on: no drift. Measured
  // 0.11 deg/s (L2 touch-downs 2346-4370 ms); with ld_hold.g_pr = 0 +30 deg/s.
  std::vector<double> t_td, h_td;
  for (const auto& [t0, da] : stances(c, "L2")) {
    if (t0 < 2000) continue;
    size_t k = 0;
    while (c.t[k] < t0) ++k;
    t_td.push_back(t0);
    h_td.push_back(c.path.heading_deg[k]);
  }
  ASSERT_GE(t_td.size(), 5u);
  const double drift = (h_td.back() - h_td.front()) / (t_td.back() - t_td.front()) * 1000.0;  // deg/s
  EXPECT_LT(std::abs(drift), 2.0) << "forward heading drift " << drift << " deg/s";
  EXPECT_LT(std::abs(heading_change(c)), 10.0);  // over the turning window 3000-5000 ms: 2.9 deg measured
  EXPECT_GT(c.path.x_mm.back(), 50.0) << "walks forward";  // 108 mm measured (-29 mm with g_pr = 0)
}

TEST(CurveWalking, BackwardSteppingTurnsMoreThanSidewardStepping) {
  double back = heading_change(run_curve({"L2.command.backward_ms=3000", "L2.command.forward_ms=1e9"}));
  double side = heading_change(
      run_curve({"L2.command.backward_ms=1e9", "L2.command.forward_ms=1e9", "L2.command.sideward_ms=3000"}));
  // Section 3.2.3: "the angle of turning is much larger in the first case". Measured over
  // 3000-5000 ms: backward 290 deg, sideward 132 deg (L2 held at alpha = 111.6 deg), forward
  // walking 2.9 deg (test above), so both are turns towards the inner leg.
  EXPECT_GT(side, 60.0);  // towards the inner (left) leg
  EXPECT_GT(back, 1.5 * side);
}
