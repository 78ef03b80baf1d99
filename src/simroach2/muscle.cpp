#include "simroach2/muscle.hpp"

#include <cmath>

#include "common/error.hpp"

namespace phasmid::simroach2 {

double ActivationCurve::force_N(double v_mV) const {
  const double volts = 1e-3;
  return amplitude_N / (1.0 + std::exp(steepness_per_V * (x_offset_mV - v_mV) * volts)) + y_offset_mN * 1e-3;
}

double tension_rate_N_per_s(const MuscleParameters& m, double tension_N, double length_m, double velocity_m_per_s,
                            double active_force_N) {
  if (!(m.b_Ns_per_m > 0) || !(m.k_se_N_per_m > 0)) throw Error("simroach2 muscle: k_se and b must be positive");
  const double stretch = length_m - m.rest_length_m;
  return m.k_se_N_per_m / m.b_Ns_per_m *
         (m.k_pe_N_per_m * stretch + m.b_Ns_per_m * velocity_m_per_s -
          (1.0 + m.k_pe_N_per_m / m.k_se_N_per_m) * tension_N + active_force_N);
}

double isometric_tension_N(const MuscleParameters& m, double length_m, double active_force_N) {
  return (m.k_pe_N_per_m * (length_m - m.rest_length_m) + active_force_N) * m.k_se_N_per_m /
         (m.k_se_N_per_m + m.k_pe_N_per_m);
}

}  // namespace phasmid::simroach2
