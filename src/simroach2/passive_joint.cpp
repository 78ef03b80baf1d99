#include "simroach2/passive_joint.hpp"

#include <cmath>

#include "common/error.hpp"

namespace phasmid::simroach2 {

double equivalent_torsional_stiffness(double k, double r, double alpha) {
  const double s = std::sin(alpha);
  return k * r * r * s * s;
}

double natural_frequency_rad_per_s(double k_t, double inertia) {
  if (!(inertia > 0)) throw Error("simroach2 design: inertia must be positive");
  return std::sqrt(k_t / inertia);
}

double torsional_damping(double k_t, double inertia, double zeta) {
  return 2.0 * zeta * natural_frequency_rad_per_s(k_t, inertia) * inertia;
}

double linear_damping_from_torsional(double c_t, double r, double alpha) {
  const double s = std::sin(alpha);
  if (r * s == 0) throw Error("simroach2 design: spring acts through the joint axis (r sin(alpha) = 0)");
  return c_t / (r * r * s * s);
}

double SpringGeometry::spring_length_m(double theta) const {
  return std::sqrt(proximal_m * proximal_m + distal_m * distal_m - 2.0 * proximal_m * distal_m * std::cos(theta));
}

double SpringGeometry::alpha_rad(double theta) const {
  const double length = spring_length_m(theta);
  const double sin_alpha = proximal_m * std::sin(theta) / length;
  // The angle at the distal attachment is obtuse when the proximal point lies beyond the foot
  // of the perpendicular; sin is the same either way, which is all eqs. (19)-(20) need.
  const double cos_alpha = (distal_m * distal_m + length * length - proximal_m * proximal_m) / (2.0 * distal_m * length);
  return std::atan2(sin_alpha, cos_alpha);
}

DampingOverRange critical_damping_over_range(double k, double inertia, const SpringGeometry& g, double theta_min,
                                             double theta_max, int n) {
  if (n < 2) throw Error("simroach2 design: need at least 2 angles over the range");
  if (!(g.proximal_m > 0 && g.distal_m > 0)) throw Error("simroach2 design: attachment distances must be positive");
  DampingOverRange out;
  for (int i = 0; i < n; ++i) {
    const double theta = theta_min + (theta_max - theta_min) * i / (n - 1);
    const double alpha = g.alpha_rad(theta);
    const double kt = equivalent_torsional_stiffness(k, g.distal_m, alpha);
    const double c = linear_damping_from_torsional(torsional_damping(kt, inertia), g.distal_m, alpha);
    out.theta_rad.push_back(theta);
    out.alpha_rad.push_back(alpha);
    out.k_t.push_back(kt);
    out.c.push_back(c);
    if (i == 0 || c > out.c_max_Ns_per_m) {
      out.c_max_Ns_per_m = c;
      out.theta_at_max_rad = theta;
    }
  }
  return out;
}

}  // namespace phasmid::simroach2
