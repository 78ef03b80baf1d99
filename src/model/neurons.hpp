#pragma once
// Neuron and synapse equations of Knops (2013) Sections 2.1-2.2, templated on the scalar
// type so that the same code gives values (double) and exact derivatives (ceres::Jet).
// Units: V in mV, conductances in nS, capacitance in pF, currents in pA, time in ms.
#include <cmath>

#include "model/exp_batch.hpp"

namespace phasmid::model {

// Eq. (2.1): z_inf(V) = 1 / (1 + exp(gamma_z (V - V_z))), z = m, h, s.
template <class T, class P>
T boltzmann(const T& V, const P& V_half, const P& gamma) {
  using std::exp;
  return T(1.0) / (T(1.0) + exp(gamma * (V - V_half)));
}

// Parameters of the non-spiking NaP neuron (CPG neurons and interneurons, Section 2.1,
// Tables A.1-A.3), as scalars of type P (double or Jet).
template <class P>
struct NapNeuronParams {
  P C_m, epsilon, g_NaP, E_Na, V_hm, gamma_m, V_hh, gamma_h, V_tau_h, gamma_tau, g_L, E_L, g_app, E_app;
};

// Every exponential of the right-hand side depends on states and parameters only, never on
// another exponential. So a network evaluation runs in phases: first each component writes
// the arguments x of its exponentials (*_exp_args, a fixed count per component), then all of
// them are taken in one batch, e = exp(x) (model/exp_batch.hpp, vectorised for double), then
// the equations read e. The one-call forms below do all three for a single component.

// NaP neuron: m_inf, h_inf (2.1) and the two halves of cosh in tau_h.
constexpr int kNapExpArgs = 4;
template <class T, class P>
void nap_exp_args(const NapNeuronParams<P>& q, const T& V, T* a) {
  a[0] = q.gamma_m * (V - q.V_hm);
  a[1] = q.gamma_h * (V - q.V_hh);
  a[2] = q.gamma_tau * (V - q.V_tau_h);
  a[3] = -a[2];
}

// Right-hand side of the NaP neuron given the total synaptic current I_syn (pA) and the
// exponentials e of nap_exp_args.
// The inactivation follows dh/dt = eps (h_inf - h) cosh(gamma_tau (V - V_tau_h)) (docs/model.md "Neurons":
// tau_h(V) = 1 / (eps cosh(...)), the form of Daun et al. 2009 that Table A.1's
// "time constant coefficient" eps belongs to).
// g_app: the drive's conductance, q.g_app or that plus a modulation's (a network's extra drive).
template <class T, class P, class G>
void nap_neuron_rhs(const NapNeuronParams<P>& q, const G& g_app, const T& V, const T& h, const T& I_syn,
                    const T* e, T& dV, T& dh) {
  T m_inf = T(1.0) / (T(1.0) + e[0]);  // (2.1)
  T h_inf = T(1.0) / (T(1.0) + e[1]);
  T I_NaP = q.g_NaP * m_inf * h * (V - q.E_Na);
  T I_L = q.g_L * (V - q.E_L);
  T I_app = g_app * (V - q.E_app);
  dV = -(I_NaP + I_L + I_syn + I_app) / q.C_m;
  dh = q.epsilon * (h_inf - h) * (0.5 * (e[2] + e[3]));
}

template <class T, class P>
void nap_neuron_rhs(const NapNeuronParams<P>& q, const T& V, const T& h, const T& I_syn, const T* e, T& dV, T& dh) {
  nap_neuron_rhs(q, q.g_app, V, h, I_syn, e, dV, dh);
}

template <class T, class P>
void nap_neuron_rhs(const NapNeuronParams<P>& q, const T& V, const T& h, const T& I_syn, T& dV, T& dh) {
  T a[kNapExpArgs], e[kNapExpArgs];
  nap_exp_args(q, V, a);
  exp_each(a, e, kNapExpArgs);
  nap_neuron_rhs(q, V, h, I_syn, e, dV, dh);
}

// Hodgkin-Huxley motoneuron with Traub Na/K currents and adaptation current q (eqs. 2.2-2.18,
// Tables A.5-A.9). Eq. (2.14) as printed repeats b_h3, b_h2; the Traub form uses a_m3, a_m2.
template <class P>
struct MotoneuronParams {
  P C_m, g_Na, E_Na, Na_am1, Na_am2, Na_am3, Na_bm1, Na_bm2, Na_bm3, Na_ah1, Na_ah2, Na_ah3, Na_bh1, Na_bh2,
      Na_bh3, g_K, E_K, K_am1, K_am2, K_am3, K_bm1, K_bm2, K_bm3, g_q, E_q, V_hq, s_q, r_q, g_L, E_L, g_app, E_app;
};

// x / (e - 1) with e = exp(c x), its removable singularity at x = 0 handled (limit 1/c).
template <class T, class P>
T exprel_ratio(const T& x, const P& c, const T& e) {
  using std::abs;
  if (abs(x) < 1e-7) return T(1.0) / c - x / 2.0;
  return x / (e - 1.0);
}

template <class T, class P>
T exprel_ratio(const T& x, const P& c) {
  using std::exp;
  return exprel_ratio(x, c, T(exp(c * x)));
}

// Motoneuron: the six Traub rates (2.10)-(2.15) and m_q,inf (2.17).
constexpr int kMotoneuronExpArgs = 7;
template <class T, class P>
void motoneuron_exp_args(const MotoneuronParams<P>& q, const T& V, T* a) {
  a[0] = q.Na_am3 * (q.Na_am2 - V);
  a[1] = q.Na_bm3 * (q.Na_bm2 - V);
  a[2] = q.Na_ah3 * (q.Na_ah2 - V);
  a[3] = q.Na_bh3 * (q.Na_bh2 - V);
  a[4] = q.K_am3 * (q.K_am2 - V);
  a[5] = q.K_bm3 * (q.K_bm2 - V);
  a[6] = q.s_q * (V - q.V_hq);
}

// State order: V, m_Na, h_Na, m_K, m_q; e from motoneuron_exp_args.
template <class T, class P, class G>
void motoneuron_rhs(const MotoneuronParams<P>& q, const G& g_app, const T* s, const T& I_syn, const T* e, T* ds) {
  const T& V = s[0];
  const T &mNa = s[1], &hNa = s[2], &mK = s[3], &mq = s[4];
  T a_mNa = q.Na_am1 * exprel_ratio(T(q.Na_am2 - V), q.Na_am3, e[0]);      // (2.10)
  T b_mNa = q.Na_bm1 * exprel_ratio(T(q.Na_bm2 - V), q.Na_bm3, e[1]);      // (2.11)
  T a_hNa = q.Na_ah1 * e[2];                                               // (2.12)
  T b_hNa = q.Na_bh1 / (e[3] + 1.0);                                       // (2.13)
  T a_mK = q.K_am1 * exprel_ratio(T(q.K_am2 - V), q.K_am3, e[4]);          // (2.14), corrected
  T b_mK = q.K_bm1 * e[5];                                                 // (2.15)
  T mq_inf = T(1.0) / (T(1.0) + e[6]);                                     // (2.17)
  T I_Na = q.g_Na * mNa * mNa * hNa * (V - q.E_Na);                        // (2.3)
  T I_K = q.g_K * mK * (V - q.E_K);                                        // (2.4)
  T I_q = q.g_q * mq * (V - q.E_q);                                        // (2.5)
  T I_L = q.g_L * (V - q.E_L);                                             // (2.6)
  T I_app = g_app * (V - q.E_app);                                         // (2.8)
  ds[0] = -(I_Na + I_K + I_q + I_L + I_syn + I_app) / q.C_m;               // (2.2)
  ds[1] = a_mNa * (1.0 - mNa) - b_mNa * mNa;                               // (2.9)
  ds[2] = a_hNa * (1.0 - hNa) - b_hNa * hNa;
  ds[3] = a_mK * (1.0 - mK) - b_mK * mK;
  ds[4] = q.r_q * (mq_inf - mq);                                           // (2.16)
}

template <class T, class P>
void motoneuron_rhs(const MotoneuronParams<P>& q, const T* s, const T& I_syn, const T* e, T* ds) {
  motoneuron_rhs(q, q.g_app, s, I_syn, e, ds);
}

template <class T, class P>
void motoneuron_rhs(const MotoneuronParams<P>& q, const T* s, const T& I_syn, T* ds) {
  T a[kMotoneuronExpArgs], e[kMotoneuronExpArgs];
  motoneuron_exp_args(q, s[0], a);
  exp_each(a, e, kMotoneuronExpArgs);
  motoneuron_rhs(q, s, I_syn, e, ds);
}

// Rate (non-spiking) motoneuron, phasmid's reduced formulation (docs/model.md, "Rate
// motoneurons"): the membrane equation (2.2) without the fast spike currents I_Na, I_K, so V
// is the subthreshold ("would-be") potential set by leak, drive, synapses and adaptation. The
// firing rate is the Traub MN's own f-V relation, normalised to f_ref = 100 Hz:
//   R(V) = (softplus_w(V - V_th) / dV_ref)^p,   softplus_w(x) = w log(1 + exp(x / w)),
// i.e. a class-I onset at V_th (w only smooths the corner) and a sublinear rise above it
// (R = 1 at V_th + dV_ref). A graded rate matters because partly inhibited MNs fire at
// 20-40 Hz (the hind depressor before its burst); a step at a single rate cannot show that.
// The adaptation gate follows the time average of its spike-driven input, dm_q/dt =
// r_q (q_max R - m_q) (q_max: mean of m_q,inf(V) during tonic firing at f_ref, which is
// proportional to the rate). Computed in log space so that the far subthreshold range neither
// overflows nor loses its derivative.
// State order: V, m_q. Uses C_m, g_q, E_q, r_q, g_L, E_L, g_app, E_app of MotoneuronParams.
template <class T, class P>
T motoneuron_rate(const T& V, const P& V_th, const P& width, const P& dV_ref, const P& exponent) {
  using std::exp;
  using std::log;
  T z = (V - V_th) / width;
  // log(softplus(z)): z for large z, z itself (softplus ~ exp(z)) far below the onset.
  T log_sp = z > 30.0 ? T(log(z)) : (z < -30.0 ? z : T(log(log(1.0 + exp(z)))));
  T log_R = exponent * (log_sp + log(width) - log(dV_ref));
  // Far below the onset R and dR/dV would underflow to exactly 0; the solver's Jacobian
  // sparsity pattern is sampled numerically (src/solver/simulator.cpp), so a 0 there would
  // drop the MN -> muscle entries. Below log R = -600 the exponent continues as
  // -600 - log(1 + (-600 - log R)) (C1, R < 1e-260: no effect on the dynamics).
  if (log_R < -600.0) log_R = -600.0 - log(1.0 - 600.0 - log_R);
  return exp(log_R);
}

template <class T, class P, class G>
void rate_motoneuron_rhs(const MotoneuronParams<P>& q, const G& g_app, const P& q_max, const T* s, const T& I_syn,
                         const T& R, T* ds) {
  const T& V = s[0];
  const T& mq = s[1];
  T I_q = q.g_q * mq * (V - q.E_q);
  T I_L = q.g_L * (V - q.E_L);
  T I_app = g_app * (V - q.E_app);
  ds[0] = -(I_q + I_L + I_syn + I_app) / q.C_m;
  ds[1] = q.r_q * (q_max * R - mq);
}

}  // namespace phasmid::model
