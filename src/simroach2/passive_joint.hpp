#pragma once
// Passive spring and damper of each SimRoach2 joint (supplement Sect. 3.3, 3.5.1) and the
// design calculators of Sect. 3.5.1, eqs. (15)-(20). SI units: N, m, s, rad, kg m^2.
#include <vector>

namespace phasmid::simroach2 {

// Table 2 prints damping in mg/s; 1 mg/s = 1e-6 kg/s = 1e-6 N s/m.
constexpr double kNsPerM_per_mgPerS = 1e-6;

struct PassiveSpringDamper {
  double stiffness_N_per_m = 0;  // Table 2
  double damping_Ns_per_m = 0;   // Table 2 (converted from mg/s)
  double rest_length_m = 0;      // Table 1 (same attachment points as the flexor)

  // Tension along the spring: k (L - L_rest) + c dL/dt (AnimatLab linear spring and damper).
  double force_N(double length_m, double velocity_m_per_s) const {
    return stiffness_N_per_m * (length_m - rest_length_m) + damping_Ns_per_m * velocity_m_per_s;
  }
};

// Eq. (19): k_t = k r^2 sin^2(alpha).
double equivalent_torsional_stiffness(double k_N_per_m, double r_m, double alpha_rad);
// Eq. (16): omega_n = sqrt(k_t / I).
double natural_frequency_rad_per_s(double k_t_Nm_per_rad, double inertia_kg_m2);
// Eq. (15): c_t = 2 zeta omega_n I.
double torsional_damping(double k_t_Nm_per_rad, double inertia_kg_m2, double zeta = 1.0);
// Eq. (20): c = c_t / (r^2 sin^2(alpha)).
double linear_damping_from_torsional(double c_t_Nms_per_rad, double r_m, double alpha_rad);

// Planar attachment geometry: the spring runs from a point at distance `proximal_m` from the
// joint on the proximal segment to a point at distance `distal_m` on the distal segment; the
// joint angle theta is the angle between the segments at the joint.
struct SpringGeometry {
  double proximal_m = 0;
  double distal_m = 0;  // r of eqs. (18)-(20)
  double spring_length_m(double theta_rad) const;
  // alpha: angle between the spring and the distal segment (law of sines).
  double alpha_rad(double theta_rad) const;
};

struct DampingOverRange {
  std::vector<double> theta_rad, alpha_rad, k_t, c;  // per sampled angle
  double c_max_Ns_per_m = 0;                          // the value SimRoach2 picks
  double theta_at_max_rad = 0;
};

// Sect. 3.5.1: critical linear damping (zeta = 1) at every sampled angle of [theta_min,
// theta_max] (n >= 2 samples, inclusive); the largest one critically damps every posture.
DampingOverRange critical_damping_over_range(double k_N_per_m, double inertia_kg_m2, const SpringGeometry& g,
                                             double theta_min_rad, double theta_max_rad, int n);

}  // namespace phasmid::simroach2
