#pragma once
// Hill-type muscle of SimRoach2 (AnimatLab 2 linear Hill model, SI units: N, m, s) with the
// sigmoid stimulus-tension (activation) curve. Supplement Sect. 2.3 and 3.5.2-3.5.3.
namespace phasmid::simroach2 {

struct ActivationCurve {
  double amplitude_N = 0;     // chosen per muscle by optimisation (Table 3)
  double x_offset_mV = -50;   // Sect. 2.3
  double steepness_per_V = 300;  // Sect. 2.3; AnimatLab applies it to the voltage in volts
  double y_offset_mN = 0;     // Table 3; constrained so that the force is zero at -60 mV

  // Active force A(V) = amplitude / (1 + exp(steepness (x_offset - V))) + y_offset, in N.
  double force_N(double v_mV) const;
};

struct MuscleParameters {
  double k_se_N_per_m = 45.0;    // series stiffness, Sect. 2.3 (Bluemel et al. 2012 Fig. 3)
  double k_pe_N_per_m = 11.24;   // parallel stiffness, Sect. 2.3
  double b_Ns_per_m = 0.1;       // damping, Sect. 2.3 / 3.5.2
  double rest_length_m = 0;      // Table 1 (flexor / extensor rest length)
  ActivationCurve activation;
};

// dT/dt = (k_se / b) (k_pe (x - x_rest) + b dx/dt - (1 + k_pe / k_se) T + A), N/s.
// The form of AnimatLab 2 (Shadmehr and Arbib 1992); Sect. 3.5.2 describes its k_se/b factor
// and b*dx/dt term.
double tension_rate_N_per_s(const MuscleParameters& m, double tension_N, double length_m, double velocity_m_per_s,
                            double active_force_N);

// Isometric steady state at length x: T = (k_pe (x - x_rest) + A) k_se / (k_se + k_pe).
double isometric_tension_N(const MuscleParameters& m, double length_m, double active_force_N);

}  // namespace phasmid::simroach2
