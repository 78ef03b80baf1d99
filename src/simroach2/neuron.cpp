#include "simroach2/neuron.hpp"

#include "common/error.hpp"

namespace phasmid::simroach2 {

double tau_h_ms(const NeuronParameters& p, double V) {
  return p.tau_h_max_ms * p.h(V) * std::sqrt(p.h.A * std::exp(p.h.S * (V - p.h.E)));
}

double i_nap_nA(const NeuronParameters& p, double V, double h) {
  return p.g_na_uS * p.m(V) * h * (p.e_na_mV - V);
}

double dV_dt(const NeuronParameters& p, double V, double h, double i_syn_nA, double i_app_nA) {
  const double c = p.capacitance_nF();
  if (!(c > 0)) throw Error("simroach2 neuron: time_constant_ms and relative_size_uS must be positive");
  const double i_leak = p.relative_size_uS * (p.rest_potential_mV - V);  // eq. (2)
  return (i_leak + i_syn_nA + i_nap_nA(p, V, h) + i_app_nA) / c;
}

double dh_dt(const NeuronParameters& p, double V, double h) {
  if (p.g_na_uS == 0) return 0.0;
  return (p.h(V) - h) / tau_h_ms(p, V);
}

}  // namespace phasmid::simroach2
