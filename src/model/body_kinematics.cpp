#include "model/body_kinematics.hpp"

#include <cmath>

#include "common/units.hpp"

namespace phasmid::model {

BodyPath integrate_body_path(const std::vector<double>& t, const std::vector<double>& aL, const std::vector<double>& bL,
                             const std::vector<double>& aR, const std::vector<double>& bR, double thr, double reach,
                             double half_width) {
  const size_t n = t.size();
  BodyPath p;
  p.x_mm.assign(n, 0.0);
  p.y_mm.assign(n, 0.0);
  p.heading_deg.assign(n, 0.0);
  double x = 0, y = 0, th = 0;
  for (size_t k = 1; k < n; ++k) {
    const double dt = t[k] - t[k - 1];  // ms
    auto push = [&](const std::vector<double>& a, const std::vector<double>& b, double& lever) {
      const double am = 0.5 * (a[k] + a[k - 1]) * units::kRadPerDeg;
      lever = half_width + reach * std::sin(am);
      if (0.5 * (b[k] + b[k - 1]) >= thr) return 0.0;           // swing: no push
      return reach * std::sin(am) * (a[k] - a[k - 1]) * units::kRadPerDeg;  // mm over dt (retraction > 0)
    };
    double wL, wR;
    const double dL = push(aL, bL, wL), dR = push(aR, bR, wR);
    const double ds = 0.5 * (dL + dR);              // forward displacement, mm
    const double dth = 0.5 * (dR / wR - dL / wL);  // yaw, rad (left foot pushing back turns left)
    x += ds * std::cos(th + 0.5 * dth);
    y += ds * std::sin(th + 0.5 * dth);
    th += dth;
    (void)dt;
    p.x_mm[k] = x;
    p.y_mm[k] = y;
    p.heading_deg[k] = th / units::kRadPerDeg;
  }
  return p;
}

}  // namespace phasmid::model
