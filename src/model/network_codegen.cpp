// NetworkModel::rhs_source: the double evaluation of some components as straight-line C++
// (model/compiled_rhs.hpp compiles it). It mirrors eval_components step by step (the same
// exponentials in the same order, the same neuron functions of model/neurons.hpp, the same
// sums in the same order) with every state and parameter index a literal, so that the
// compiled function returns the generic evaluation's values bit for bit.
#include <algorithm>
#include <cstdio>
#include <iterator>
#include <limits>
#include <ostream>
#include <sstream>

#include "common/error.hpp"
#include "common/units.hpp"
#include "model/compiled_rhs.hpp"
#include "model/network_model.hpp"

namespace phasmid::model {

namespace {

// A double as a C++ literal that reads back exactly.
std::string literal(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", v);
  return buf;
}

std::string P(size_t i) { return "p[" + std::to_string(i) + "]"; }

// A parameter struct's initialiser from its n indices, in the struct's field order.
std::string brace(const size_t* idx, size_t n) {
  std::string s = "{";
  for (size_t k = 0; k < n; ++k) s += (k ? ", " : "") + P(idx[k]);
  return s + "}";
}

}  // namespace

// Writes the phases of NetworkModel::eval_components for components c, each as the generic
// function of the same name does (exp_args, currents_and_drives, neuron_equations,
// joint_equations), reading the exponentials in the order they were written. States are read
// and written where `layout` puts them (Y, D).
class NetworkCodegen {
 public:
  NetworkCodegen(const NetworkModel& m, const NetworkComponents& c, const RhsLayout& layout, std::ostream& o)
      : m_(m), c_(c), o_(o) {
    const size_t n = m.num_states();
    y_.assign(n, kUnread);
    d_.assign(n, kUnread);
    if (layout.own.empty())
      for (size_t i = 0; i < n; ++i) y_[i] = d_[i] = static_cast<long>(i);
    for (size_t i = 0; i < layout.own.size(); ++i) y_[layout.own[i]] = d_[layout.own[i]] = static_cast<long>(i);
    for (size_t i = 0; i < layout.inputs.size(); ++i) y_[layout.inputs[i]] = -1 - static_cast<long>(i);
  }

  void exp_args() const {
    for (size_t si : c_.synapses) {
      const Synapse& s = m_.synapses_[si];
      if (s.gate.neuron != kNoIndex)
        o_ << "  a[n++] = " << P(s.gate.gamma) << " * (" << Y(V(s.gate.neuron)) << " - " << P(s.gate.V_h) << ");\n";
      o_ << "  a[n++] = " << P(s.q.gamma) << " * (" << Y(V(s.pre)) << " - " << P(s.q.V_h) << ");\n";
    }
    for (size_t mi : c_.modulations)
      for (const Condition& cd : m_.modulations_[mi].conditions) {
        if (cd.kind == Condition::AngleBelow)
          o_ << "  a[n++] = -(" << P(cd.threshold) << " - " << Y(cd.angle_state) << " * " << deg_ << ") / " << P(cd.width) << ";\n";
        if (cd.kind == Condition::AngleAbove)
          o_ << "  a[n++] = -(" << Y(cd.angle_state) << " * " << deg_ << " - " << P(cd.threshold) << ") / " << P(cd.width) << ";\n";
      }
    for (size_t j = 0; j < c_.neurons.size(); ++j) {
      const Neuron& nr = m_.neurons_[c_.neurons[j]];
      if (!nr.motoneuron) {
        // NapIdx lists the indices in NapNeuronParams' order (as NetworkModel::gather_params reads them).
        static_assert(sizeof(NapIdx) / sizeof(size_t) == sizeof(NapNeuronParams<double>) / sizeof(double));
        o_ << "  const NapNeuronParams<double> q" << j << brace(&nr.nap.C_m, sizeof(NapIdx) / sizeof(size_t)) << ";\n";
        o_ << "  nap_exp_args(q" << j << ", " << Y(nr.state) << ", a + n);\n  n += kNapExpArgs;\n";
        continue;
      }
      o_ << "  const MotoneuronParams<double> q" << j << brace(nr.mn.v, std::size(nr.mn.v)) << ";\n";
      if (!m_.rate_mn_) o_ << "  motoneuron_exp_args(q" << j << ", " << Y(nr.state) << ", a + n);\n  n += kMotoneuronExpArgs;\n";
    }
    if (!m_.rate_mn_)
      for (size_t mi : c_.muscles)
        o_ << "  a[n++] = -(" << Y(V(m_.muscles_[mi].motoneuron)) << " - " << P(m_.act_V_) << ") / " << P(m_.act_w_) << ";\n";
  }

  // The per-neuron and per-muscle sums as locals.
  void currents_and_drives() const {
    for (size_t i : c_.neurons) o_ << "  double I_syn" << i << " = 0.0, g_extra" << i << " = 0.0;\n";
    for (size_t i : c_.muscles) o_ << "  double tone" << i << " = 0.0;\n";
    for (size_t si : c_.synapses) {
      const Synapse& s = m_.synapses_[si];
      o_ << "  {\n    double g = " << P(s.q.g) << ";\n";
      if (s.gate.neuron != kNoIndex) o_ << "    g *= 1.0 - " << P(s.gate.strength) << " * (1.0 / (1.0 + e[k++]));\n";
      o_ << "    I_syn" << s.post << " += g * (1.0 / (1.0 + e[k++])) * (" << Y(V(s.post)) << " - " << P(s.q.E) << ");\n  }\n";
    }
    for (size_t mi : c_.modulations) {
      const Modulation& m = m_.modulations_[mi];
      o_ << "  {\n    double gate = 1.0;\n";
      for (const Condition& cd : m.conditions) {
        switch (cd.kind) {
          case Condition::AngleBelow:
          case Condition::AngleAbove: o_ << "    gate *= 1.0 / (1.0 + e[k++]);\n"; break;
          case Condition::TimeAfter: o_ << "    if (t < " << P(cd.threshold) << ") gate = 0.0;\n"; break;
          case Condition::TimeBefore: o_ << "    if (t >= " << P(cd.threshold) << ") gate = 0.0;\n"; break;
        }
      }
      const std::string target = (m.target == Modulation::RestTone ? "tone" : "g_extra") + std::to_string(m.neuron);
      if (m.reference == kNoIndex) o_ << "    " << target << " += " << P(m.delta) << " * gate;\n  }\n";
      else o_ << "    " << target << " += (" << P(m.delta) << " - " << P(m.reference) << ") * gate;\n  }\n";
    }
  }

  void neuron_equations() const {
    for (size_t j = 0; j < c_.neurons.size(); ++j) {
      const size_t i = c_.neurons[j];
      const Neuron& nr = m_.neurons_[i];
      const std::string q = "q" + std::to_string(j), y = "&" + Y(nr.state), ydot = "&" + D(nr.state);
      contiguous(nr.state, m_.neuron_state_count(nr));
      if (!nr.motoneuron) {
        o_ << "  nap_neuron_rhs(" << q << ", double(" << q << ".g_app + g_extra" << i << "), " << Y(nr.state) << ", "
           << Y(nr.state + 1) << ", I_syn" << i << ", e + k, " << D(nr.state) << ", " << D(nr.state + 1)
           << ");\n  k += kNapExpArgs;\n";
        continue;
      }
      o_ << "  const double g_app" << i << " = " << q << ".g_app + g_extra" << i << ";\n";
      if (m_.rate_mn_) {
        const RateMotoneuronIdx& r = m_.rate_;
        o_ << "  const double R" << i << " = motoneuron_rate(" << Y(nr.state) << ", " << P(r.V_th) << ", " << P(r.width)
           << ", " << P(r.dV_ref) << ", " << P(r.exponent) << ");\n";
        o_ << "  rate_motoneuron_rhs(" << q << ", g_app" << i << ", " << P(r.q_max) << ", " << y << ", I_syn" << i << ", R"
           << i << ", " << ydot << ");\n";
      } else {
        o_ << "  motoneuron_rhs(" << q << ", g_app" << i << ", " << y << ", I_syn" << i << ", e + k, " << ydot
           << ");\n  k += kMotoneuronExpArgs;\n";
      }
    }
    for (size_t mi : c_.muscles) {
      const Muscle& m = m_.muscles_[mi];
      const std::string a = Y(m.activation), out = D(m.activation);
      if (m_.rate_mn_) {
        o_ << "  " << out << " = " << P(m_.rate_.gain) << " * R" << m.motoneuron << " * (1.0 - " << a << ") - "
           << P(m_.act_b_) << " * " << a << ";\n";
      } else {
        o_ << "  {\n    double S = 1.0 / (1.0 + e[k++]);\n    " << out << " = (" << P(m_.act_a0_) << " + " << P(m_.act_b_)
           << ") * S * (1.0 - " << a << ") - " << P(m_.act_b_) << " * (1.0 - S) * " << a << ";\n  }\n";
      }
    }
  }

  // The acceleration from the header function the generic evaluation calls (model/mechanics.hpp),
  // with the joint type a constant so that the compiler keeps only its branch.
  void joint_equations(const Joint& j) const {
    const Muscle &mi = m_.muscles_[j.muscle_inc], &md = m_.muscles_[j.muscle_dec];
    const std::string ai = Y(mi.activation), ad = Y(md.activation);
    static const char* const type[] = {"JointType::Thc", "JointType::Ctr", "JointType::Fti"};
    o_ << "  {\n    double k_inc = " << spring(mi, ai, ad, j.muscle_inc) << ";\n";
    o_ << "    double k_dec = " << spring(md, ad, ai, j.muscle_dec) << ";\n";
    o_ << "    const double* g[7] = {";
    for (size_t k = 0; k < 7; ++k) o_ << (k ? ", " : "") << "&" << P(j.mech.geom[k]);
    o_ << "};\n";
    o_ << "    " << D(j.angle_state) << " = " << Y(j.velocity_state) << " * 1e-3;\n";
    o_ << "    " << D(j.velocity_state) << " = joint_type_acceleration(" << type[static_cast<int>(j.mech.type)] << ", g, "
       << P(j.mech.inertia) << ", " << P(j.mech.b_v) << ", " << Y(j.angle_state) << ", " << Y(j.velocity_state)
       << ", k_inc, k_dec) * 1e-3;\n  }\n";
  }

 private:
  size_t V(size_t neuron) const { return m_.neurons_[neuron].state; }
  // State i as the function reads it: an own state y[local] or an input u[j].
  std::string Y(size_t i) const {
    if (y_[i] == kUnread) throw Error("internal: compiled rhs reads state " + std::to_string(i) + ", not in its layout");
    return y_[i] >= 0 ? "y[" + std::to_string(y_[i]) + "]" : "u[" + std::to_string(-1 - y_[i]) + "]";
  }
  std::string D(size_t i) const {
    if (d_[i] == kUnread) throw Error("internal: compiled rhs writes state " + std::to_string(i) + ", not its own");
    return "ydot[" + std::to_string(d_[i]) + "]";
  }
  // The neuron functions take a pointer to a neuron's states: they must stay adjacent in the layout.
  void contiguous(size_t first, size_t count) const {
    for (size_t k = 1; k < count; ++k)
      if (y_[first + k] != y_[first] + static_cast<long>(k) || d_[first + k] != d_[first] + static_cast<long>(k))
        throw Error("internal: compiled rhs: the states of a neuron are not adjacent in the part's layout");
  }
  // A muscle's spring constant with activation a, the antagonist's a_other and its rest-tone
  // release (NetworkModel::joint_equations).
  std::string spring(const Muscle& m, const std::string& a, const std::string& a_other, size_t muscle) const {
    return P(m.k_rest) + " + (" + P(m.k_active) + " - " + P(m.k_rest) + ") * " + a + " - tone" + std::to_string(muscle) +
           " * " + P(m.k_rest) + " * (1.0 - " + a + ") * (1.0 - " + a_other + ")";
  }

  static constexpr long kUnread = std::numeric_limits<long>::min();
  const NetworkModel& m_;
  const NetworkComponents& c_;
  std::ostream& o_;
  std::vector<long> y_, d_;  // per full state index: >= 0 own y[i], < 0 input u[-1 - i], kUnread
  const std::string deg_ = literal(units::kDegPerRad);
};

std::string NetworkModel::rhs_source(const NetworkComponents& c, const RhsLayout& layout, const std::string& symbol) const {
  std::ostringstream o;
  const size_t n_args = std::max<size_t>(1, max_exp_args());
  o << compiled_rhs_preamble() << "extern \"C\" void " << symbol
    << "(double t, const double* y, const double* u, const double* p, double* ydot, const PhasmidRhsContext* ctx) {\n"
    << "  (void)t;\n  (void)u;\n  double a[" << n_args << "], e[" << n_args << "];\n  size_t n = 0, k = 0;\n";
  const NetworkCodegen w(*this, c, layout, o);
  w.exp_args();
  o << "  ctx->exp_each(a, e, n);\n";
  w.currents_and_drives();
  w.neuron_equations();
  for (size_t ji : c.joints) w.joint_equations(joints_[ji]);
  o << "}\n";
  return o.str();
}

}  // namespace phasmid::model
