#include "model/stiff_rates.hpp"

#include <algorithm>
#include <cmath>

namespace phasmid::model {

namespace {

// The total rate alpha + beta of the spiking motoneuron's gates m_Na, h_Na, m_K (eqs. 2.10-2.15,
// as in motoneuron_rhs) at potential V.
void motoneuron_gate_rates(const MotoneuronParams<double>& q, double V, double* k) {
  k[0] = q.Na_am1 * exprel_ratio(q.Na_am2 - V, q.Na_am3) + q.Na_bm1 * exprel_ratio(q.Na_bm2 - V, q.Na_bm3);
  k[1] = q.Na_ah1 * std::exp(q.Na_ah3 * (q.Na_ah2 - V)) + q.Na_bh1 / (std::exp(q.Na_bh3 * (q.Na_bh2 - V)) + 1.0);
  k[2] = q.K_am1 * exprel_ratio(q.K_am2 - V, q.K_am3) + q.K_bm1 * std::exp(q.K_bm3 * (q.K_bm2 - V));
}

// g_tot / C of a neuron without its synapses, and (options.gates) its gates' rates.
void neuron_rates(const NetworkModel& model, const Neuron& n, const double* y, const double* p, double* kappa,
                  const StiffRateOptions& options) {
  const double V = y[n.state];
  if (!n.motoneuron) {
    const NapIdx& x = n.nap;
    const double m_inf = boltzmann(V, p[x.V_hm], p[x.gamma_m]);
    kappa[n.state] += (p[x.g_NaP] * m_inf * y[n.state + 1] + p[x.g_L] + p[x.g_app]) / p[x.C_m];
    if (options.gates) kappa[n.state + 1] = p[x.epsilon] * std::cosh(p[x.gamma_tau] * (V - p[x.V_tau_h]));
    return;
  }
  MotoneuronParams<double> q;
  double* f = &q.C_m;
  for (int k = 0; k < 32; ++k) f[k] = p[n.mn.v[k]];
  const double* s = &y[n.state];
  double g = q.g_q * s[model.rate_motoneurons() ? 1 : 4] + q.g_L + q.g_app;
  if (!model.rate_motoneurons()) {
    g += q.g_Na * s[1] * s[1] * s[2] + q.g_K * s[3];
    if (options.gates) motoneuron_gate_rates(q, V, &kappa[n.state + 1]);
  }
  kappa[n.state] += g / q.C_m;
}

}  // namespace

void stiff_rates(const NetworkModel& model, const double* y, const double* p, double* kappa,
                 const StiffRateOptions& options) {
  std::fill(kappa, kappa + model.num_states(), 0.0);
  const auto& neurons = model.neurons();
  for (const Synapse& s : model.synapses()) {
    const Neuron& post = neurons[s.post];
    const double C = post.motoneuron ? p[post.mn.v[0]] : p[post.nap.C_m];
    kappa[post.state] += p[s.q.g] * boltzmann(y[neurons[s.pre].state], p[s.q.V_h], p[s.q.gamma]) / C;
  }
  for (const Neuron& n : neurons) neuron_rates(model, n, y, p, kappa, options);
}

std::vector<double> stiff_offsets(const NetworkModel& model, const double* p) {
  std::vector<double> c(model.num_states(), 0.0);
  // E_L is entry 29 of a motoneuron's parameters (MotoneuronParams order).
  for (const Neuron& n : model.neurons()) c[n.state] = n.motoneuron ? p[n.mn.v[29]] : p[n.nap.E_L];
  return c;
}

}  // namespace phasmid::model
