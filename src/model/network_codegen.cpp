// NetworkModel::rhs_source: the double evaluation of some components as straight-line C++
// (model/compiled_rhs.hpp compiles it). It mirrors eval_components step by step (the same
// exponentials in the same order, the same neuron functions of model/neurons.hpp, the same
// sums in the same order) with every state and parameter index a literal, so that the
// compiled function returns the generic evaluation's values bit for bit.
#include <algorithm>
#include <cstdio>
#include <iterator>
#include <ostream>
#include <sstream>

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
std::string Y(size_t i) { return "y[" + std::to_string(i) + "]"; }

// A parameter struct's initialiser from its n indices, in the struct's field order.
std::string brace(const size_t* idx, size_t n) {
  std::string s = "{";
  for (size_t k = 0; k < n; ++k) s += (k ? ", " : "") + P(idx[k]);
  return s + "}";
}

}  // namespace

// Writes the phases of NetworkModel::eval_components for components c, each as the generic
// function of the same name does (exp_args, currents_and_drives, neuron_equations,
// joint_equations), reading the exponentials in the order they were written.
class NetworkCodegen {
 public:
  NetworkCodegen(const NetworkModel& m, const NetworkComponents& c, std::ostream& o) : m_(m), c_(c), o_(o) {}

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
      const std::string q = "q" + std::to_string(j), s = std::to_string(nr.state), s1 = std::to_string(nr.state + 1);
      if (!nr.motoneuron) {
        o_ << "  nap_neuron_rhs(" << q << ", double(" << q << ".g_app + g_extra" << i << "), y[" << s << "], y[" << s1
           << "], I_syn" << i << ", e + k, ydot[" << s << "], ydot[" << s1 << "]);\n  k += kNapExpArgs;\n";
        continue;
      }
      o_ << "  const double g_app" << i << " = " << q << ".g_app + g_extra" << i << ";\n";
      if (m_.rate_mn_) {
        const RateMotoneuronIdx& r = m_.rate_;
        o_ << "  const double R" << i << " = motoneuron_rate(y[" << s << "], " << P(r.V_th) << ", " << P(r.width) << ", "
           << P(r.dV_ref) << ", " << P(r.exponent) << ");\n";
        o_ << "  rate_motoneuron_rhs(" << q << ", g_app" << i << ", " << P(r.q_max) << ", &y[" << s << "], I_syn" << i
           << ", R" << i << ", &ydot[" << s << "]);\n";
      } else {
        o_ << "  motoneuron_rhs(" << q << ", g_app" << i << ", &y[" << s << "], I_syn" << i << ", e + k, &ydot[" << s
           << "]);\n  k += kMotoneuronExpArgs;\n";
      }
    }
    for (size_t mi : c_.muscles) {
      const Muscle& m = m_.muscles_[mi];
      const std::string a = Y(m.activation), out = "ydot[" + std::to_string(m.activation) + "]";
      if (m_.rate_mn_) {
        o_ << "  " << out << " = " << P(m_.rate_.gain) << " * R" << m.motoneuron << " * (1.0 - " << a << ") - "
           << P(m_.act_b_) << " * " << a << ";\n";
      } else {
        o_ << "  {\n    double S = 1.0 / (1.0 + e[k++]);\n    " << out << " = (" << P(m_.act_a0_) << " + " << P(m_.act_b_)
           << ") * S * (1.0 - " << a << ") - " << P(m_.act_b_) << " * (1.0 - S) * " << a << ";\n  }\n";
      }
    }
  }

  void joint_equations(const Joint& j, size_t ji) const {
    const Muscle &mi = m_.muscles_[j.muscle_inc], &md = m_.muscles_[j.muscle_dec];
    const std::string ai = Y(mi.activation), ad = Y(md.activation);
    o_ << "  {\n    double k_inc = " << spring(mi, ai, ad, j.muscle_inc) << ";\n";
    o_ << "    double k_dec = " << spring(md, ad, ai, j.muscle_dec) << ";\n";
    o_ << "    ydot[" << j.angle_state << "] = " << Y(j.velocity_state) << " * 1e-3;\n";
    o_ << "    ydot[" << j.velocity_state << "] = ctx->joint_acceleration(ctx->model, " << ji << ", p, "
       << Y(j.angle_state) << ", " << Y(j.velocity_state) << ", k_inc, k_dec) * 1e-3;\n  }\n";
  }

 private:
  size_t V(size_t neuron) const { return m_.neurons_[neuron].state; }
  // A muscle's spring constant with activation a, the antagonist's a_other and its rest-tone
  // release (NetworkModel::joint_equations).
  std::string spring(const Muscle& m, const std::string& a, const std::string& a_other, size_t muscle) const {
    return P(m.k_rest) + " + (" + P(m.k_active) + " - " + P(m.k_rest) + ") * " + a + " - tone" + std::to_string(muscle) +
           " * " + P(m.k_rest) + " * (1.0 - " + a + ") * (1.0 - " + a_other + ")";
  }

  const NetworkModel& m_;
  const NetworkComponents& c_;
  std::ostream& o_;
  const std::string deg_ = literal(units::kDegPerRad);
};

std::string NetworkModel::rhs_source(const NetworkComponents& c, const std::string& symbol) const {
  std::ostringstream o;
  const size_t n_args = std::max<size_t>(1, max_exp_args());
  o << compiled_rhs_preamble() << "extern \"C\" void " << symbol
    << "(double t, const double* y, const double* p, double* ydot, const PhasmidRhsContext* ctx) {\n"
    << "  (void)t;\n  double a[" << n_args << "], e[" << n_args << "];\n  size_t n = 0, k = 0;\n";
  const NetworkCodegen w(*this, c, o);
  w.exp_args();
  o << "  ctx->exp_each(a, e, n);\n";
  w.currents_and_drives();
  w.neuron_equations();
  for (size_t ji : c.joints) w.joint_equations(joints_[ji], ji);
  o << "}\n";
  return o.str();
}

double NetworkModel::joint_acceleration_of(const void* model, size_t joint, const double* p, double angle,
                                           double omega, double k_inc, double k_dec) {
  const auto& m = *static_cast<const NetworkModel*>(model);
  return joint_acceleration(m.joints_[joint].mech, p, angle, omega, k_inc, k_dec);
}

}  // namespace phasmid::model
