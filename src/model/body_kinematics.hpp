#pragma once
// Kinematic body model for curve walking with two middle legs (Knops 2013 Section 3.2.3,
// Figs. 3.13-3.14; docs/walking_model.md). Assumptions (the dissertation used a physics
// engine with passive, frictionless front and hind legs; phasmid uses kinematics only):
//  - a foot in stance (beta below the leg's ground-contact threshold) pushes the body along
//    its long axis with the fore-aft speed of the foot relative to the body,
//    v_i = -d/dt (reach cos alpha_i) = reach sin(alpha_i) dalpha_i/dt (retraction: v_i > 0);
//  - a foot in swing and the passive legs exert no fore-aft push; the body does not slip
//    sideways (non-holonomic, like a differential drive);
//  - forward speed u = (v_L + v_R) / 2 and yaw rate omega = (v_R - v_L) / (2 w) summed over
//    the stance feet, w = half_width + reach sin(alpha) the lateral lever of the foot.
// Backward stepping of the inner leg reverses its push (turning on the spot), sideward
// stepping removes it (a wider curve).
#include <vector>

namespace phasmid::model {

struct BodyPath {
  std::vector<double> x_mm, y_mm, heading_deg;  // centre of the body; heading 0 = +x, left turn > 0
};

// The body's pose while integrating: x, y (mm), heading (rad).
struct BodyPose {
  double x = 0.0, y = 0.0, theta = 0.0;
};
// One sample of integrate_body_path: the pose moved from the previous sample (index 0 of each
// pair, degrees) to the current one (index 1), for callers that read the samples in blocks.
void body_path_step(BodyPose& pose, const double alpha_left[2], const double beta_left[2], const double alpha_right[2],
                    const double beta_right[2], double beta_thr_deg, double reach_mm, double half_width_mm);

// Angles in degrees sampled at times t (ms); beta_thr_deg the ground-contact threshold.
BodyPath integrate_body_path(const std::vector<double>& t, const std::vector<double>& alpha_left,
                             const std::vector<double>& beta_left, const std::vector<double>& alpha_right,
                             const std::vector<double>& beta_right, double beta_thr_deg, double reach_mm,
                             double half_width_mm);

}  // namespace phasmid::model
