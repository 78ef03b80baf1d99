#include "model/network_model.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace phasmid::model {

size_t NetworkModel::add_nap_neuron(const std::string& name, const NapIdx& q, double V0, double h0) {
  Neuron n{name, false, add_state(name + ".V", "mV"), q, {}};
  add_state(name + ".h", "1");
  y0_.push_back(V0);
  y0_.push_back(h0);
  neurons_.push_back(n);
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
  return joints_.size() - 1;
}

size_t NetworkModel::neuron_index(const std::string& name) const {
  for (size_t i = 0; i < neurons_.size(); ++i)
    if (neurons_[i].name == name) return i;
  throw Error("unknown neuron '" + name + "'");
}

std::vector<double> NetworkModel::initial_state(const std::vector<double>& p) const {
  std::vector<double> y = y0_;
  for (const Joint& j : joints_) y[j.angle_state] = p[j.angle0] * M_PI / 180.0;
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

}  // namespace phasmid::model
