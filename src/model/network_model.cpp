#include "model/network_model.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "common/units.hpp"
#include "model/compiled_rhs.hpp"

namespace phasmid::model {

size_t NetworkModel::add_nap_neuron(const std::string& name, const NapIdx& q, double V0, double h0) {
  Neuron n{name, false, add_state(name + ".V", "mV"), q, {}};
  add_state(name + ".h", "1");
  y0_.push_back(V0);
  y0_.push_back(h0);
  neurons_.push_back(n);
  structure_.neurons.push_back({name, n.state});
  all_.neurons.push_back(neurons_.size() - 1);
  return neurons_.size() - 1;
}

size_t NetworkModel::add_motoneuron(const std::string& name, const MotoneuronIdx& q) {
  Neuron n{name, true, add_state(name + ".V", "mV"), {}, q};
  if (rate_mn_) {  // rate formulation: V and the adaptation gate only
    add_state(name + ".m_q", "1");
    for (double v : {-65.0, 0.0}) y0_.push_back(v);
  } else {
    for (const char* g : {".m_Na", ".h_Na", ".m_K", ".m_q"}) add_state(name + g, "1");
    // Resting values of the Traub gates near -65 mV.
    for (double v : {-65.0, 0.02, 0.98, 0.05, 0.0}) y0_.push_back(v);
  }
  neurons_.push_back(n);
  structure_.neurons.push_back({name, n.state});
  all_.neurons.push_back(neurons_.size() - 1);
  return neurons_.size() - 1;
}

MotoneuronModel parse_motoneuron_model(const std::string& s) {
  if (s == "spiking") return MotoneuronModel::Spiking;
  if (s == "rate") return MotoneuronModel::Rate;
  throw Error("unknown motoneuron formulation '" + s + "' (expected spiking or rate)");
}

size_t NetworkModel::add_muscle(size_t motoneuron, size_t k_rest, size_t k_active, const std::string& name) {
  size_t a = add_state(name + ".activation", "1");
  y0_.push_back(0.0);
  muscles_.push_back({motoneuron, a, k_rest, k_active});
  all_.muscles.push_back(muscles_.size() - 1);
  return muscles_.size() - 1;
}

size_t NetworkModel::add_joint(const std::string& leg, const JointMechanics& mech, size_t muscle_inc,
                               size_t muscle_dec, double angle0_deg) {
  JointNaming n = joint_naming(mech.type);
  size_t a = add_state(mech.prefix + "." + n.angle, "rad");
  size_t w = add_state(mech.prefix + "." + n.angle + "_dot", "rad/s");
  y0_.push_back(NAN);  // from the angle0 parameter
  y0_.push_back(0.0);
  size_t a0 = define({mech.prefix + "." + n.angle + "0", angle0_deg, "deg", "documented choice (docs/model.md)",
                      "initial joint angle", -180, 180});
  joints_.push_back({mech, leg, a, w, muscle_inc, muscle_dec, a0});
  angles_.push_back({leg, joint_name(mech.type), a, w});
  all_.joints.push_back(joints_.size() - 1);
  return joints_.size() - 1;
}

size_t NetworkModel::neuron_index(const std::string& name) const {
  for (size_t i = 0; i < neurons_.size(); ++i)
    if (neurons_[i].name == name) return i;
  throw Error("unknown neuron '" + name + "'");
}

std::vector<double> NetworkModel::initial_state(const std::vector<double>& p) const {
  std::vector<double> y = y0_;
  for (const Joint& j : joints_) y[j.angle_state] = units::deg_to_rad(p[j.angle0]);
  return y;
}

std::vector<double> NetworkModel::breakpoints(const std::vector<double>& p, double t_end) const {
  std::vector<double> b;
  for (const Modulation& m : modulations_)
    for (const Condition& c : m.conditions)
      if ((c.kind == Condition::TimeAfter || c.kind == Condition::TimeBefore) && p[c.threshold] > 0 && p[c.threshold] < t_end) b.push_back(p[c.threshold]);
  // One command may step several drives at once: report each time once (sorted).
  std::sort(b.begin(), b.end());
  b.erase(std::unique(b.begin(), b.end()), b.end());
  return b;
}

namespace {
// Union-find over state indices.
struct DisjointSets {
  std::vector<size_t> parent;
  explicit DisjointSets(size_t n) : parent(n) {
    for (size_t i = 0; i < n; ++i) parent[i] = i;
  }
  size_t find(size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(size_t a, size_t b) { parent[find(a)] = find(b); }
};

// One part's equations (or the whole model's: an empty layout). Compiled, a part of a partition
// runs its generated function on packed vectors; rhs on full vectors packs them first.
class NetworkPart final : public OdeModelPart {
 public:
  NetworkPart(const NetworkModel& m, NetworkComponents c, RhsLayout layout = {})
      : model_(m), comp_(std::move(c)), layout_(std::move(layout)) {}
  bool compile(std::string* why) override {
    compiled_ = compile_rhs(model_.rhs_source(comp_, layout_, "phasmid_rhs"), "phasmid_rhs", why);
    if (compiled_) {
      y_.resize(layout_.own.size());
      u_.resize(layout_.inputs.size());
      f_.resize(layout_.own.size());
    }
    return compiled_ != nullptr;
  }
  bool packed() const override { return compiled_ && !layout_.own.empty(); }
  void bind(const double* p) override {
    model_.bind_neurons(comp_, p, bound_);
    bound_p_ = p;
  }
  void rhs_packed(double t, const double* y, const double* u, const double* p, double* ydot) const override {
    compiled_(t, y, u, p, ydot, &kContext);
  }
  void rhs(double t, const double* y, const double* p, double* ydot) const override {
    if (!compiled_) return model_.eval_components(comp_, t, y, p, ydot, p == bound_p_ ? &bound_ : nullptr);
    if (layout_.own.empty()) return compiled_(t, y, nullptr, p, ydot, &kContext);
    for (size_t i = 0; i < layout_.own.size(); ++i) y_[i] = y[layout_.own[i]];
    for (size_t i = 0; i < layout_.inputs.size(); ++i) u_[i] = y[layout_.inputs[i]];
    compiled_(t, y_.data(), u_.data(), p, f_.data(), &kContext);
    for (size_t i = 0; i < layout_.own.size(); ++i) ydot[layout_.own[i]] = f_[i];
  }
  void rhs(double t, const JetK* y, const JetK* p, JetK* ydot) const override {
    model_.eval_components(comp_, t, y, p, ydot);
  }

 private:
  static constexpr PhasmidRhsContext kContext{static_cast<void (*)(const double*, double*, size_t)>(exp_each)};
  const NetworkModel& model_;
  NetworkComponents comp_;
  RhsLayout layout_;
  BoundNeuronParams bound_;
  const double* bound_p_ = nullptr;  // the vector bound_ was gathered from
  PhasmidRhsFn compiled_ = nullptr;
  mutable std::vector<double> y_, u_, f_;  // rhs' packed copies (a part serves one run at a time)
};
}  // namespace

void NetworkModel::bind_neurons(const NetworkComponents& c, const double* p, BoundNeuronParams& out) const {
  out.nap.assign(c.neurons.size(), {});
  out.mn.assign(c.neurons.size(), {});
  for (size_t j = 0; j < c.neurons.size(); ++j) {
    const Neuron& n = neurons_[c.neurons[j]];
    if (n.motoneuron) gather_params(n.mn, p, out.mn[j]);
    else gather_params(n.nap, p, out.nap[j]);
  }
}

size_t NetworkModel::neuron_state_count(const Neuron& n) const {
  return n.motoneuron && !rate_mn_ ? 5 : 2;
}

size_t NetworkModel::modulation_target_state(const Modulation& m) const {
  return m.target == Modulation::RestTone ? muscles_[m.neuron].activation : neurons_[m.neuron].state;
}

ModelPartition NetworkModel::partition(PartitionGrain grain) const {
  const size_t n = num_states();
  const bool split = grain == PartitionGrain::Neurons && !rate_mn_;
  // A coupling, not a join: a synapse onto a spiking motoneuron from a neuron of the network.
  auto couples = [&](const Synapse& s) { return split && neurons_[s.post].motoneuron && !neurons_[s.pre].motoneuron; };
  DisjointSets sets(n);
  for (const Neuron& nr : neurons_)
    for (size_t k = 1; k < neuron_state_count(nr); ++k) sets.join(nr.state, nr.state + k);
  for (const Synapse& s : synapses_) {
    if (couples(s)) continue;
    sets.join(neurons_[s.pre].state, neurons_[s.post].state);
    if (s.gate.neuron != kNoIndex) sets.join(neurons_[s.gate.neuron].state, neurons_[s.post].state);
  }
  for (const Muscle& m : muscles_) sets.join(m.activation, neurons_[m.motoneuron].state);
  for (const Joint& j : joints_) {
    sets.join(j.angle_state, j.velocity_state);
    sets.join(j.angle_state, muscles_[j.muscle_inc].activation);
    sets.join(j.angle_state, muscles_[j.muscle_dec].activation);
  }
  // Parts numbered in the order of their first state.
  ModelPartition P;
  std::vector<size_t> part_of_root(n, kNoIndex), part_of(n);
  for (size_t i = 0; i < n; ++i) {
    size_t& k = part_of_root[sets.find(i)];
    if (k == kNoIndex) {
      k = P.states.size();
      P.states.emplace_back();
    }
    part_of[i] = k;
    P.states[k].push_back(i);
  }
  P.inputs.assign(P.size(), {});
  P.names.assign(P.size(), "");
  auto read = [&](size_t k, size_t state) {
    if (part_of[state] != k && std::find(P.inputs[k].begin(), P.inputs[k].end(), state) == P.inputs[k].end())
      P.inputs[k].push_back(state);
  };
  for (const Modulation& m : modulations_)
    for (const Condition& c : m.conditions)
      if (c.kind == Condition::AngleBelow || c.kind == Condition::AngleAbove)
        read(part_of[modulation_target_state(m)], c.angle_state);
  for (const Synapse& s : synapses_)
    if (couples(s)) {
      read(part_of[neurons_[s.post].state], neurons_[s.pre].state);
      if (s.gate.neuron != kNoIndex) read(part_of[neurons_[s.post].state], neurons_[s.gate.neuron].state);
    }
  for (const Joint& j : joints_) {
    std::string& name = P.names[part_of[j.angle_state]];
    name += (name.empty() ? "" : "+") + j.mech.prefix;
  }
  for (size_t k = 0; k < P.size(); ++k)
    if (P.names[k].empty()) P.names[k] = states_[P.states[k].front()].name;
  // A part without a joint or a spiking motoneuron is a network of neurons: stiff and smooth.
  if (split) {
    P.stiff.assign(P.size(), 1);
    for (const Joint& j : joints_) P.stiff[part_of[j.angle_state]] = 0;
    for (const Neuron& nr : neurons_)
      if (nr.motoneuron) P.stiff[part_of[nr.state]] = 0;
  }
  return P;
}

std::unique_ptr<OdeModelPart> NetworkModel::make_whole() const { return std::make_unique<NetworkPart>(*this, all_); }

std::unique_ptr<OdeModelPart> NetworkModel::make_part(const ModelPartition& P, size_t k) const {
  std::vector<char> mine(num_states(), 0);
  for (size_t i : P.states.at(k)) mine[i] = 1;
  NetworkComponents c;
  for (size_t i = 0; i < synapses_.size(); ++i)
    if (mine[neurons_[synapses_[i].post].state]) c.synapses.push_back(i);
  for (size_t i = 0; i < modulations_.size(); ++i)
    if (mine[modulation_target_state(modulations_[i])]) c.modulations.push_back(i);
  for (size_t i = 0; i < neurons_.size(); ++i)
    if (mine[neurons_[i].state]) c.neurons.push_back(i);
  for (size_t i = 0; i < muscles_.size(); ++i)
    if (mine[muscles_[i].activation]) c.muscles.push_back(i);
  for (size_t i = 0; i < joints_.size(); ++i)
    if (mine[joints_[i].angle_state]) c.joints.push_back(i);
  return std::make_unique<NetworkPart>(*this, std::move(c), RhsLayout{P.states[k], P.inputs.at(k)});
}

}  // namespace phasmid::model
