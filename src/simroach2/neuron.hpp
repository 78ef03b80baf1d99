#pragma once
// AnimatLab 2 non-spiking neuron with optional persistent sodium current, SimRoach2
// supplement Sect. 3.2, eqs. (1)-(4), (6)-(8). Units (Sect. 3.2.1): mV, ms, nF, uS, nA.
#include <cmath>

namespace phasmid::simroach2 {

// Sigmoid of eq. (7): z_inf(V) = 1 / (1 + A exp(S (V - E))).
struct GateSigmoid {
  double A = 1;    // 1
  double S = 0;    // 1/mV
  double E = 0;    // mV
  double operator()(double V) const { return 1.0 / (1.0 + A * std::exp(S * (V - E))); }
};

struct NeuronParameters {
  double time_constant_ms = 0;  // tau_m = C_m / G_m
  double relative_size_uS = 0;  // G_m ("relative size" in AnimatLab 2)
  double rest_potential_mV = 0; // E_r
  double g_na_uS = 0;           // G_Na; 0 for all but CPG half-centres
  double e_na_mV = 0;           // E_Na
  GateSigmoid m;                // m_inf, eq. (7)
  GateSigmoid h;                // h_inf, eq. (7)
  double tau_h_max_ms = 0;      // eq. (8)

  double capacitance_nF() const { return time_constant_ms * relative_size_uS; }
};

// tau_h(V) = tau_h,max * h_inf(V) * sqrt(A_h exp(S_h (V - E_h))), eq. (8).
double tau_h_ms(const NeuronParameters& p, double V);

// Persistent sodium current, eq. (4), nA.
double i_nap_nA(const NeuronParameters& p, double V, double h);

// dV/dt in mV/ms from eq. (1) with the leak of eq. (2); i_syn_nA is eq. (3) summed over
// the incoming synapses, i_app_nA the external stimulus.
double dV_dt(const NeuronParameters& p, double V, double h, double i_syn_nA, double i_app_nA);

// dh/dt in 1/ms, eq. (6); zero when the neuron has no persistent sodium channel.
double dh_dt(const NeuronParameters& p, double V, double h);

}  // namespace phasmid::simroach2
