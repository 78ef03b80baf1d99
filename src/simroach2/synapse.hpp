#pragma once
// Piecewise-linear conductance synapse of AnimatLab 2, SimRoach2 supplement eq. (5):
// G_s = G_max * min(max((V_pre - E_lo) / (E_hi - E_lo), 0), 1); its current enters eq. (3).
#include <algorithm>

namespace phasmid::simroach2 {

struct SynapseParameters {
  double g_max_uS = 0;     // G_max
  double e_lo_mV = 0;      // lower threshold E_lo
  double e_hi_mV = 0;      // upper threshold E_hi
  double e_rev_mV = 0;     // equilibrium potential E_s (e.g. -20 mV for Table 4, 300 mV for Table 5)
};

inline double conductance_uS(const SynapseParameters& s, double v_pre_mV) {
  const double u = (v_pre_mV - s.e_lo_mV) / (s.e_hi_mV - s.e_lo_mV);
  return s.g_max_uS * std::min(std::max(u, 0.0), 1.0);
}

// Current into the postsynaptic neuron, nA (one term of eq. 3).
inline double current_nA(const SynapseParameters& s, double v_pre_mV, double v_post_mV) {
  return conductance_uS(s, v_pre_mV) * (s.e_rev_mV - v_post_mV);
}

}  // namespace phasmid::simroach2
