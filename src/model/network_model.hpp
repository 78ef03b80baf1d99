#pragma once
// The neuro-mechanical network (Knops 2013 Section 2.5): NaP interneurons and CPG neurons,
// Hodgkin-Huxley motoneurons, sigmoid synapses, spike-driven muscle activation and joint
// mechanics, assembled as data (lists of components holding parameter and state indices)
// and evaluated by one templated right-hand side.
//
// Two smooth formulations replace switches of the dissertation (docs/model.md):
//  - muscle activation: the spring constant follows (2.83) "during an action potential" and
//    (2.84) otherwise; "during an action potential" is the sigmoid S(V_MN) of the motoneuron
//    voltage (midpoint muscle.V_spike, width muscle.spike_width) instead of a hard test;
//  - sensory thresholds (beta < beta_thr, gamma > gamma_thr): sigmoids of width `*.width_deg`.
// Both converge to the switched model as the widths go to zero; they keep the right-hand
// side differentiable so that CVODES sensitivities need no jump conditions.
// Optionally (MotoneuronModel::Rate) the motoneurons are non-spiking rate cells and the muscle
// activation follows their firing rate (docs/model.md, "Rate motoneurons").
#include <string>
#include <type_traits>
#include <vector>

#include "common/units.hpp"
#include "model/joint.hpp"
#include "model/neurons.hpp"
#include "model/ode_model.hpp"

namespace phasmid::model {

constexpr size_t kNoIndex = static_cast<size_t>(-1);

struct NapIdx {  // parameter indices of a NaP neuron (Section 2.1)
  size_t C_m, epsilon, g_NaP, E_Na, V_hm, gamma_m, V_hh, gamma_h, V_tau_h, gamma_tau, g_L, E_L, g_app, E_app;
};
struct MotoneuronIdx {  // parameter indices of a motoneuron (Section 2.2), same order as MotoneuronParams
  size_t v[32];
};
struct SynapseIdx { size_t g, V_h, gamma, E; };

// Motoneuron formulation (config key [model] motoneuron): the Hodgkin-Huxley MNs of Section
// 2.2 with spike-driven muscle activation (2.83)/(2.84), or phasmid's rate formulation
// (docs/model.md, "Rate motoneurons") without spikes: 2 states per MN instead of 5.
enum class MotoneuronModel { Spiking, Rate };
MotoneuronModel parse_motoneuron_model(const std::string& s);
// Parameters of the rate formulation: f-V relation R(V) (onset, onset smoothing, depolarisation
// above onset for the reference rate, exponent), adaptation drive and muscle activation rate
// at the reference rate.
struct RateMotoneuronIdx { size_t V_th, width, dV_ref, exponent, q_max, gain; };

struct Neuron {
  std::string name;   // "middle.fti.cpg_flx"
  bool motoneuron;
  size_t state;       // first state (V)
  NapIdx nap{};
  MotoneuronIdx mn{};
};

// Optional presynaptic inhibition of a synapse (Fig. 3.11, Toth et al. 2012): the synaptic
// conductance is multiplied by 1 - p[strength] * s_inf(V_gate) with the gating neuron's
// voltage V_gate and the sigmoid s_inf of (2.20) with p[V_h], p[gamma].
struct PresynapticGate {
  size_t neuron = kNoIndex;  // gating neuron (kNoIndex: ungated)
  size_t strength = 0, V_h = 0, gamma = 0;
};

struct Synapse {
  size_t pre, post;  // neuron indices
  SynapseIdx q;
  PresynapticGate gate{};
};

// A condition of a sensory or central switch; all conditions of a Modulation multiply.
struct Condition {
  enum Kind { AngleBelow, AngleAbove, TimeAfter, TimeBefore } kind;
  size_t angle_state = 0;  // rad (AngleBelow/AngleAbove)
  size_t threshold = 0;    // parameter: deg, or ms for TimeAfter/TimeBefore
  size_t width = 0;        // parameter: deg (sigmoid width)
};

// Adds p[delta] (nS) to a neuron's applied conductance while the conditions hold; with a
// reference parameter it adds p[delta] - p[reference] instead, so that `delta` can name the
// value the conductance is raised (or lowered) to, e.g. IN4: 0.60 -> 3.90 nS.
// Target RestTone: `neuron` is a muscle index and the sum is the muscle's rest-tone release w
// (dimensionless, see Muscle).
struct Modulation {
  enum Target { Drive, RestTone };
  size_t neuron;
  size_t delta;
  std::vector<Condition> conditions;
  size_t reference = kNoIndex;
  Target target = Drive;
};

// Spring constant k = k_rest + (k_active - k_rest) a. With a rest-tone release w (0 unless a
// RestTone Modulation sets it) the resting part needs an active antagonist (the joint's other
// muscle, activation a'): k = k_active a + k_rest (1 - a) (1 - w + w a'). w = 1 lets both k of
// a joint decay to 0 with the same rate b when both motoneurons are silent, as in (2.84),
// which keeps their ratio and hence the joint's equilibrium angle (sideward stepping,
// docs/walking_model.md).
struct Muscle {
  size_t motoneuron;   // neuron index
  size_t activation;   // state index of the activation a in [0, 1]
  size_t k_rest, k_active;  // parameters: spring constant at a = 0 and a = 1 (mN/mm^2)
};

struct Joint {
  JointMechanics mech;
  std::string leg;
  size_t angle_state, velocity_state;
  size_t muscle_inc, muscle_dec;  // muscle indices
  size_t angle0;                  // parameter: initial angle (deg)
};

// The components whose equations one evaluation covers: all of them, or one part of a
// ModelPartition (synapses by postsynaptic neuron, modulations by target, muscles by
// activation state, joints by angle state).
struct NetworkComponents {
  std::vector<size_t> synapses, modulations, neurons, muscles, joints;
};

// The neurons' parameters of some components gathered once (NetworkModel::bind_neurons), by
// position in NetworkComponents::neurons: a double evaluation given them reads them in place
// instead of gathering each neuron's 14 or 32 values by index on every call, a gather that
// would otherwise repeat at every right-hand side of a run. They hold for one parameter
// vector; whoever changes its values binds again.
struct BoundNeuronParams {
  std::vector<NapNeuronParams<double>> nap;
  std::vector<MotoneuronParams<double>> mn;
};

// Per-thread working storage of one evaluation (NetworkModel::eval_components), indexed by
// neuron or muscle; nap and mn hold the evaluated neurons' parameters, gathered once per
// evaluation unless bound, by position in NetworkComponents::neurons (a part's few stay in
// the L1 cache).
template <class T>
struct NetworkScratch {
  std::vector<T> I_syn, g_extra, tone_release, rate_mn, args, ex;
  std::vector<NapNeuronParams<T>> nap;
  std::vector<MotoneuronParams<T>> mn;
  const BoundNeuronParams* bound = nullptr;  // set for double evaluations given bound parameters
};

class NetworkModel : public OdeModelT<NetworkModel> {
 public:
  explicit NetworkModel(std::string kind) : kind_(std::move(kind)) {}
  std::string kind() const override { return kind_; }

  // ---- assembly -------------------------------------------------------------------------
  size_t define(Parameter p) { return params_.add(std::move(p)); }
  size_t add_nap_neuron(const std::string& name, const NapIdx& q, double V0, double h0);
  // Call before adding motoneurons: they then get the rate formulation's 2 states.
  void set_rate_motoneurons(const RateMotoneuronIdx& r) { rate_mn_ = true; rate_ = r; }
  bool rate_motoneurons() const { return rate_mn_; }
  size_t add_motoneuron(const std::string& name, const MotoneuronIdx& q);
  size_t add_synapse(size_t pre, size_t post, const SynapseIdx& q, PresynapticGate gate = {}) {
    synapses_.push_back({pre, post, q, gate});
    all_.synapses.push_back(synapses_.size() - 1);
    return synapses_.size() - 1;
  }
  void set_synapse_gate(size_t synapse, PresynapticGate gate) { synapses_.at(synapse).gate = gate; }
  void set_synapse_params(size_t synapse, const SynapseIdx& q) { synapses_.at(synapse).q = q; }
  const std::vector<Synapse>& synapses() const { return synapses_; }
  const std::vector<Modulation>& modulations() const { return modulations_; }
  void add_modulation(Modulation m) {
    conditions_ += m.conditions.size();
    modulations_.push_back(std::move(m));
    all_.modulations.push_back(modulations_.size() - 1);
  }
  size_t add_muscle(size_t motoneuron, size_t k_rest, size_t k_active, const std::string& name);
  size_t add_joint(const std::string& leg, const JointMechanics& mech, size_t muscle_inc, size_t muscle_dec,
                   double angle0_deg);
  void set_muscle_activation_params(size_t a0, size_t b, size_t V_spike, size_t width) {
    act_a0_ = a0; act_b_ = b; act_V_ = V_spike; act_w_ = width;
  }
  // Declarations of the model's structure (OdeModel::structure()); neurons declare themselves.
  void add_contact_leg(ContactLeg leg) { structure_.contact_legs.push_back(std::move(leg)); }
  void set_contralateral_copy(ContralateralCopy c) { structure_.contralateral = c; }
  void set_body_geometry(BodyGeometry b) { structure_.body = std::move(b); }
  size_t neuron_index(const std::string& name) const;
  const std::vector<Neuron>& neurons() const { return neurons_; }
  const std::vector<Joint>& joints() const { return joints_; }
  const std::vector<Muscle>& muscles() const { return muscles_; }

  std::vector<double> initial_state(const std::vector<double>& p) const override;
  std::vector<double> breakpoints(const std::vector<double>& p, double t_end) const override;
  // Parts = the joints' networks: states joined by synapses, presynaptic gates, motoneuron ->
  // muscle -> joint; the sensory and intersegmental modulations (sigmoids of joint angles)
  // are the couplings between parts. Neurons grain, spiking motoneurons: the synapses from
  // other neurons onto motoneurons couple too (the motoneurons read the presynaptic
  // potentials), which splits each joint's network into its CPG and interneurons (stiff, no
  // spikes) and its motoneurons, muscles and mechanics.
  ModelPartition partition(PartitionGrain grain) const override;
  std::unique_ptr<OdeModelPart> make_part(const ModelPartition& partition, size_t k) const override;
  std::unique_ptr<OdeModelPart> make_whole() const override;

  template <class T>
  void eval(double t, const T* y, const T* p, T* ydot) const { eval_components(all_, t, y, p, ydot); }
  // The equations of the given components only (ydot written at their states). bound: the
  // components' neuron parameters from p (bind_neurons), used by double evaluations only.
  template <class T>
  void eval_components(const NetworkComponents& c, double t, const T* y, const T* p, T* ydot,
                       const BoundNeuronParams* bound = nullptr) const;
  void bind_neurons(const NetworkComponents& c, const double* p, BoundNeuronParams& out) const;
  // The double evaluation of c as C++ source of the function `symbol` (PhasmidRhsFn,
  // model/compiled_rhs.hpp): eval_components with every index a literal, the same values, on
  // vectors packed as `layout` says.
  std::string rhs_source(const NetworkComponents& c, const RhsLayout& layout, const std::string& symbol) const;

 private:
  template <class T>
  size_t exp_args(const NetworkComponents& comp, const T* y, const T* p, NetworkScratch<T>& sc) const;
  // The neuron parameters an evaluation reads: bound ones (double only) or sc's, gathered.
  template <class T>
  static const NapNeuronParams<T>& nap_params(const NetworkScratch<T>& sc, size_t j);
  template <class T>
  static const MotoneuronParams<T>& mn_params(const NetworkScratch<T>& sc, size_t j);
  template <class T>
  void currents_and_drives(const NetworkComponents& comp, double t, const T* y, const T* p, NetworkScratch<T>& sc,
                           size_t& k) const;
  template <class T>
  void neuron_equations(const NetworkComponents& comp, const T* y, const T* p, NetworkScratch<T>& sc, size_t& k,
                        T* ydot) const;
  template <class T>
  void joint_equations(const Joint& j, const T* y, const T* p, const NetworkScratch<T>& sc, T* ydot) const;
  // Gathered in place: a returned struct's copy read its fields back before their stores had
  // completed (store-forwarding stalls that showed in the evaluation's profile).
  template <class T>
  static void gather_params(const NapIdx& x, const T* p, NapNeuronParams<T>& q);
  template <class T>
  static void gather_params(const MotoneuronIdx& x, const T* p, MotoneuronParams<T>& q);
  // At least the exponentials of one evaluation of all components (exp_args).
  size_t max_exp_args() const {
    return 2 * synapses_.size() + conditions_ + kMotoneuronExpArgs * neurons_.size() + muscles_.size();
  }
  friend class NetworkCodegen;  // rhs_source's writer (model/network_codegen.cpp)
  size_t neuron_state_count(const Neuron& n) const;
  size_t modulation_target_state(const Modulation& m) const;

  std::string kind_;
  std::vector<Neuron> neurons_;
  std::vector<Synapse> synapses_;
  std::vector<Modulation> modulations_;
  std::vector<Muscle> muscles_;
  std::vector<Joint> joints_;
  NetworkComponents all_;   // every component, in the order added
  std::vector<double> y0_;  // default initial state of neurons and muscles
  size_t act_a0_ = 0, act_b_ = 0, act_V_ = 0, act_w_ = 0;
  bool rate_mn_ = false;
  RateMotoneuronIdx rate_{};
  size_t conditions_ = 0;  // of all modulations
};

template <class T>
T smooth_step(const T& x, const T& width) {
  using std::exp;
  return T(1.0) / (T(1.0) + exp(-x / width));
}

// Phase 1 of an evaluation (see model/neurons.hpp): the arguments of every exponential of the
// components into sc.args, in the order phase 3 reads them (and the neurons' parameters into
// sc.nap, sc.mn); returns their count.
template <class T>
size_t NetworkModel::exp_args(const NetworkComponents& comp, const T* y, const T* p, NetworkScratch<T>& sc) const {
  T* a = sc.args.data();
  for (size_t si : comp.synapses) {
    const Synapse& s = synapses_[si];
    if (s.gate.neuron != kNoIndex) *a++ = p[s.gate.gamma] * (y[neurons_[s.gate.neuron].state] - p[s.gate.V_h]);
    *a++ = p[s.q.gamma] * (y[neurons_[s.pre].state] - p[s.q.V_h]);
  }
  for (size_t mi : comp.modulations)
    for (const Condition& c : modulations_[mi].conditions) {
      if (c.kind == Condition::AngleBelow) *a++ = -T(p[c.threshold] - y[c.angle_state] * units::kDegPerRad) / p[c.width];
      if (c.kind == Condition::AngleAbove) *a++ = -T(y[c.angle_state] * units::kDegPerRad - p[c.threshold]) / p[c.width];
    }
  for (size_t j = 0; j < comp.neurons.size(); ++j) {
    const Neuron& n = neurons_[comp.neurons[j]];
    if (!n.motoneuron) {
      if (!sc.bound) gather_params(n.nap, p, sc.nap[j]);
      nap_exp_args(nap_params(sc, j), y[n.state], a);
      a += kNapExpArgs;
      continue;
    }
    if (!sc.bound) gather_params(n.mn, p, sc.mn[j]);
    if (!rate_mn_) {
      motoneuron_exp_args(mn_params(sc, j), y[n.state], a);
      a += kMotoneuronExpArgs;
    }
  }
  if (!rate_mn_)
    for (size_t mi : comp.muscles)
      *a++ = -T(y[neurons_[muscles_[mi].motoneuron].state] - p[act_V_]) / p[act_w_];
  return static_cast<size_t>(a - sc.args.data());
}

template <class T>
void NetworkModel::gather_params(const NapIdx& x, const T* p, NapNeuronParams<T>& q) {
  static_assert(sizeof(NapIdx) == 14 * sizeof(size_t) && sizeof(NapNeuronParams<T>) == 14 * sizeof(T));
  const size_t* index = &x.C_m;  // NapIdx lists the indices in NapNeuronParams' order
  T* f = &q.C_m;
  for (int k = 0; k < 14; ++k) f[k] = p[index[k]];
}

template <class T>
void NetworkModel::gather_params(const MotoneuronIdx& x, const T* p, MotoneuronParams<T>& q) {
  T* f = &q.C_m;
  for (int k = 0; k < 32; ++k) f[k] = p[x.v[k]];
}

template <class T>
const NapNeuronParams<T>& NetworkModel::nap_params(const NetworkScratch<T>& sc, size_t j) {
  if constexpr (std::is_same_v<T, double>)
    if (sc.bound) return sc.bound->nap[j];
  return sc.nap[j];
}

template <class T>
const MotoneuronParams<T>& NetworkModel::mn_params(const NetworkScratch<T>& sc, size_t j) {
  if constexpr (std::is_same_v<T, double>)
    if (sc.bound) return sc.bound->mn[j];
  return sc.mn[j];
}

template <class T>
void NetworkModel::eval_components(const NetworkComponents& comp, double t, const T* y, const T* p, T* ydot,
                                   const BoundNeuronParams* bound) const {
  // Only the entries of comp's neurons and muscles are used (synapses and modulations target them).
  thread_local NetworkScratch<T> sc;
  sc.bound = std::is_same_v<T, double> ? bound : nullptr;
  sc.I_syn.resize(neurons_.size());
  sc.g_extra.resize(neurons_.size());
  sc.nap.resize(comp.neurons.size());
  sc.mn.resize(comp.neurons.size());
  if (rate_mn_) sc.rate_mn.resize(neurons_.size());
  sc.tone_release.resize(muscles_.size());
  for (size_t i : comp.neurons) sc.I_syn[i] = sc.g_extra[i] = T(0.0);
  for (size_t i : comp.muscles) sc.tone_release[i] = T(0.0);

  // Phases 1 and 2: every exponential at once.
  sc.args.resize(max_exp_args());
  sc.ex.resize(max_exp_args());
  exp_each(sc.args.data(), sc.ex.data(), exp_args(comp, y, p, sc));
  // Phase 3, reading them in the order phase 1 wrote them.
  size_t k = 0;
  currents_and_drives(comp, t, y, p, sc, k);
  neuron_equations(comp, y, p, sc, k, ydot);
  for (size_t ji : comp.joints) joint_equations(joints_[ji], y, p, sc, ydot);
}

// Synaptic currents (2.7), with the optional presynaptic gate, and the modulations' drives and
// rest-tone releases.
template <class T>
void NetworkModel::currents_and_drives(const NetworkComponents& comp, double t, const T* y, const T* p,
                                       NetworkScratch<T>& sc, size_t& k) const {
  const T* e = sc.ex.data();
  auto logistic = [&] { return T(1.0) / (T(1.0) + e[k++]); };  // boltzmann (2.1), smooth_step
  for (size_t si : comp.synapses) {
    const Synapse& s = synapses_[si];
    T g = p[s.q.g];
    if (s.gate.neuron != kNoIndex) g *= T(1.0) - p[s.gate.strength] * logistic();
    sc.I_syn[s.post] += g * logistic() * (y[neurons_[s.post].state] - p[s.q.E]);
  }
  for (size_t mi : comp.modulations) {
    const Modulation& m = modulations_[mi];
    T gate(1.0);
    for (const Condition& c : m.conditions) {
      switch (c.kind) {
        case Condition::AngleBelow:  // smooth_step of the angle below / above the threshold
        case Condition::AngleAbove:
          gate *= logistic();
          break;
        case Condition::TimeAfter:  // central command: a step at a fixed time (a breakpoint)
          if (t < value_of(p[c.threshold])) gate = T(0.0);
          break;
        case Condition::TimeBefore:  // until a later command (a breakpoint)
          if (t >= value_of(p[c.threshold])) gate = T(0.0);
          break;
      }
    }
    std::vector<T>& target = m.target == Modulation::RestTone ? sc.tone_release : sc.g_extra;
    if (m.reference == kNoIndex) target[m.neuron] += p[m.delta] * gate;
    else target[m.neuron] += (p[m.delta] - p[m.reference]) * gate;
  }
}

// The neurons' and muscles' equations. rate_mn: each rate MN's R(V), computed once for its own
// equation and its muscle's.
template <class T>
void NetworkModel::neuron_equations(const NetworkComponents& comp, const T* y, const T* p, NetworkScratch<T>& sc,
                                    size_t& k, T* ydot) const {
  const T* e = sc.ex.data();
  for (size_t j = 0; j < comp.neurons.size(); ++j) {
    const size_t i = comp.neurons[j];
    const Neuron& n = neurons_[i];
    if (!n.motoneuron) {
      const NapNeuronParams<T>& q = nap_params(sc, j);
      nap_neuron_rhs(q, T(q.g_app + sc.g_extra[i]), y[n.state], y[n.state + 1], sc.I_syn[i], e + k, ydot[n.state],
                     ydot[n.state + 1]);
      k += kNapExpArgs;
      continue;
    }
    const MotoneuronParams<T>& q = mn_params(sc, j);
    const T g_app = q.g_app + sc.g_extra[i];
    if (rate_mn_) {
      sc.rate_mn[i] = motoneuron_rate(y[n.state], p[rate_.V_th], p[rate_.width], p[rate_.dV_ref], p[rate_.exponent]);
      rate_motoneuron_rhs(q, g_app, p[rate_.q_max], &y[n.state], sc.I_syn[i], sc.rate_mn[i], &ydot[n.state]);
    } else {
      motoneuron_rhs(q, g_app, &y[n.state], sc.I_syn[i], e + k, &ydot[n.state]);
      k += kMotoneuronExpArgs;
    }
  }
  // Spike-driven activation, eqs. (2.83)/(2.84) in terms of a = (k - k_rest)/(k_active - k_rest),
  // with S = smooth_step(V - V_spike, width); rate formulation: its average over the spikes,
  // da/dt = gain R(V) (1 - a) - b a.
  for (size_t mi : comp.muscles) {
    const Muscle& m = muscles_[mi];
    const T& a = y[m.activation];
    if (rate_mn_) {
      ydot[m.activation] = p[rate_.gain] * sc.rate_mn[m.motoneuron] * (1.0 - a) - p[act_b_] * a;
    } else {
      T S = T(1.0) / (T(1.0) + e[k++]);
      ydot[m.activation] = (p[act_a0_] + p[act_b_]) * S * (1.0 - a) - p[act_b_] * (1.0 - S) * a;
    }
  }
}

template <class T>
void NetworkModel::joint_equations(const Joint& j, const T* y, const T* p, const NetworkScratch<T>& sc, T* ydot) const {
  const Muscle& mi = muscles_[j.muscle_inc];
  const Muscle& md = muscles_[j.muscle_dec];
  const T &a_inc = y[mi.activation], &a_dec = y[md.activation];
  const T &w_inc = sc.tone_release[j.muscle_inc], &w_dec = sc.tone_release[j.muscle_dec];
  // k_rest + (k_active - k_rest) a, minus the released rest tone (see Muscle).
  T k_inc = p[mi.k_rest] + (p[mi.k_active] - p[mi.k_rest]) * a_inc - w_inc * p[mi.k_rest] * (1.0 - a_inc) * (1.0 - a_dec);
  T k_dec = p[md.k_rest] + (p[md.k_active] - p[md.k_rest]) * a_dec - w_dec * p[md.k_rest] * (1.0 - a_dec) * (1.0 - a_inc);
  ydot[j.angle_state] = y[j.velocity_state] * 1e-3;  // rad/s -> rad/ms
  ydot[j.velocity_state] = joint_acceleration(j.mech, p, y[j.angle_state], y[j.velocity_state], k_inc, k_dec) * 1e-3;
}

}  // namespace phasmid::model
