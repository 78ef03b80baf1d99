#pragma once
// Neuron and synapse equations of Knops (2013) Sections 2.1-2.2, templated on the scalar
// type so that the same code gives values (double) and exact derivatives (ceres::Jet).
// Units: V in mV, conductances in nS, capacitance in pF, currents in pA, time in ms.
#include <cmath>

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

// Right-hand side of the NaP neuron given the total synaptic current I_syn (pA).
// The inactivation follows dh/dt = eps (h_inf - h) cosh(gamma_tau (V - V_tau_h)) (docs/model.md "Neurons":
// tau_h(V) = 1 / (eps cosh(...)), the form of Daun et al. 2009 that Table A.1's
// "time constant coefficient" eps belongs to).
template <class T, class P>
void nap_neuron_rhs(const NapNeuronParams<P>& q, const T& V, const T& h, const T& I_syn, T& dV, T& dh) {
  using std::cosh;
  T m_inf = boltzmann(V, q.V_hm, q.gamma_m);
  T h_inf = boltzmann(V, q.V_hh, q.gamma_h);
  T I_NaP = q.g_NaP * m_inf * h * (V - q.E_Na);
  T I_L = q.g_L * (V - q.E_L);
  T I_app = q.g_app * (V - q.E_app);
  dV = -(I_NaP + I_L + I_syn + I_app) / q.C_m;
  dh = q.epsilon * (h_inf - h) * cosh(q.gamma_tau * (V - q.V_tau_h));
}

// Hodgkin-Huxley motoneuron with Traub Na/K currents and adaptation current q (eqs. 2.2-2.18,
// Tables A.5-A.9). Eq. (2.14) as printed repeats b_h3, b_h2; the Traub form uses a_m3, a_m2.
template <class P>
struct MotoneuronParams {
  P C_m, g_Na, E_Na, Na_am1, Na_am2, Na_am3, Na_bm1, Na_bm2, Na_bm3, Na_ah1, Na_ah2, Na_ah3, Na_bh1, Na_bh2,
      Na_bh3, g_K, E_K, K_am1, K_am2, K_am3, K_bm1, K_bm2, K_bm3, g_q, E_q, V_hq, s_q, r_q, g_L, E_L, g_app, E_app;
};

// x / (exp(c x) - 1) with its removable singularity at x = 0 handled (limit 1/c).
template <class T, class P>
T exprel_ratio(const T& x, const P& c) {
  using std::exp;
  using std::abs;
  if (abs(x) < 1e-7) return T(1.0) / c - x / 2.0;
  return x / (exp(c * x) - 1.0);
}

// State order: V, m_Na, h_Na, m_K, m_q.
template <class T, class P>
void motoneuron_rhs(const MotoneuronParams<P>& q, const T* s, const T& I_syn, T* ds) {
  using std::exp;
  const T& V = s[0];
  const T &mNa = s[1], &hNa = s[2], &mK = s[3], &mq = s[4];
  T a_mNa = q.Na_am1 * exprel_ratio(T(q.Na_am2 - V), q.Na_am3);              // (2.10)
  T b_mNa = q.Na_bm1 * exprel_ratio(T(q.Na_bm2 - V), q.Na_bm3);              // (2.11)
  T a_hNa = q.Na_ah1 * exp(q.Na_ah3 * (q.Na_ah2 - V));                       // (2.12)
  T b_hNa = q.Na_bh1 / (exp(q.Na_bh3 * (q.Na_bh2 - V)) + 1.0);               // (2.13)
  T a_mK = q.K_am1 * exprel_ratio(T(q.K_am2 - V), q.K_am3);                  // (2.14), corrected
  T b_mK = q.K_bm1 * exp(q.K_bm3 * (q.K_bm2 - V));                           // (2.15)
  T mq_inf = boltzmann(V, q.V_hq, q.s_q);                                    // (2.17)
  T I_Na = q.g_Na * mNa * mNa * hNa * (V - q.E_Na);                          // (2.3)
  T I_K = q.g_K * mK * (V - q.E_K);                                          // (2.4)
  T I_q = q.g_q * mq * (V - q.E_q);                                          // (2.5)
  T I_L = q.g_L * (V - q.E_L);                                               // (2.6)
  T I_app = q.g_app * (V - q.E_app);                                         // (2.8)
  ds[0] = -(I_Na + I_K + I_q + I_L + I_syn + I_app) / q.C_m;                 // (2.2)
  ds[1] = a_mNa * (1.0 - mNa) - b_mNa * mNa;                                 // (2.9)
  ds[2] = a_hNa * (1.0 - hNa) - b_hNa * hNa;
  ds[3] = a_mK * (1.0 - mK) - b_mK * mK;
  ds[4] = q.r_q * (mq_inf - mq);                                             // (2.16)
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

template <class T, class P>
void rate_motoneuron_rhs(const MotoneuronParams<P>& q, const P& q_max, const T* s, const T& I_syn, const T& R,
                         T* ds) {
  const T& V = s[0];
  const T& mq = s[1];
  T I_q = q.g_q * mq * (V - q.E_q);
  T I_L = q.g_L * (V - q.E_L);
  T I_app = q.g_app * (V - q.E_app);
  ds[0] = -(I_q + I_L + I_syn + I_app) / q.C_m;
  ds[1] = q.r_q * (q_max * R - mq);
}

// Synaptic current (2.7) into a cell at V from a presynaptic cell at V_pre.
template <class T, class P>
T synaptic_current(const P& g_syn, const P& V_hs, const P& gamma_s, const P& E_syn, const T& V_pre, const T& V) {
  return g_syn * boltzmann(V_pre, V_hs, gamma_s) * (V - E_syn);
}

}  // namespace phasmid::model
