#include "model/body_kinematics.hpp"

#include <cmath>

#include "common/units.hpp"

namespace phasmid::model {

void body_path_step(BodyPose& pose, const double aL[2], const double bL[2], const double aR[2], const double bR[2],
                    double thr, double reach, double half_width) {
  auto push = [&](const double a[2], const double b[2], double& lever) {
    const double am = 0.5 * (a[1] + a[0]) * units::kRadPerDeg;
    lever = half_width + reach * std::sin(am);
    if (0.5 * (b[1] + b[0]) >= thr) return 0.0;                   // swing: no push
    return reach * std::sin(am) * (a[1] - a[0]) * units::kRadPerDeg;  // mm over the sample (retraction > 0)
  };
  double wL, wR;
  const double dL = push(aL, bL, wL), dR = push(aR, bR, wR);
  const double ds = 0.5 * (dL + dR);              // forward displacement, mm
  const double dth = 0.5 * (dR / wR - dL / wL);  // yaw, rad (left foot pushing back turns left)
  pose.x += ds * std::cos(pose.theta + 0.5 * dth);
  pose.y += ds * std::sin(pose.theta + 0.5 * dth);
  pose.theta += dth;
}

BodyPath integrate_body_path(const std::vector<double>& t, const std::vector<double>& aL, const std::vector<double>& bL,
                             const std::vector<double>& aR, const std::vector<double>& bR, double thr, double reach,
                             double half_width) {
  const size_t n = t.size();
  BodyPath p;
  p.x_mm.assign(n, 0.0);
  p.y_mm.assign(n, 0.0);
  p.heading_deg.assign(n, 0.0);
  BodyPose pose;
  for (size_t k = 1; k < n; ++k) {
    const double a_l[2] = {aL[k - 1], aL[k]}, b_l[2] = {bL[k - 1], bL[k]};
    const double a_r[2] = {aR[k - 1], aR[k]}, b_r[2] = {bR[k - 1], bR[k]};
    body_path_step(pose, a_l, b_l, a_r, b_r, thr, reach, half_width);
    p.x_mm[k] = pose.x;
    p.y_mm[k] = pose.y;
    p.heading_deg[k] = pose.theta / units::kRadPerDeg;
  }
  return p;
}

}  // namespace phasmid::model
