// NetworkModel::rhs_source: the double evaluation of some components as straight-line C++
// (model/compiled_rhs.hpp compiles it). It mirrors eval_components step by step (the same
// exponentials in the same order, the same neuron functions of model/neurons.hpp, the same
// sums in the same order) with every state and parameter index a literal, so that the
// compiled function returns the generic evaluation's values bit for bit.
#include <cstdio>
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

template <size_t N>
std::string brace(const size_t (&idx)[N]) {
  std::string s = "{";
  for (size_t k = 0; k < N; ++k) s += (k ? ", " : "") + P(idx[k]);
  return s + "}";
}

}  // namespace

std::string NetworkModel::rhs_source(const NetworkComponents& c, const std::string& symbol) const {
  std::ostringstream o;
  const std::string deg = literal(units::kDegPerRad);
  o << compiled_rhs_preamble() << "extern \"C\" void " << symbol
    << "(double t, const double* y, const double* p, double* ydot, const PhasmidRhsContext* ctx) {\n"
    << "  (void)t;\n  double a[" << std::max<size_t>(1, max_exp_args()) << "], e[" << std::max<size_t>(1, max_exp_args())
    << "];\n  size_t n = 0, k = 0;\n";
  // Phase 1: the exponentials' arguments (exp_args).
  for (size_t si : c.synapses) {
    const Synapse& s = synapses_[si];
    if (s.gate.neuron != kNoIndex)
      o << "  a[n++] = " << P(s.gate.gamma) << " * (" << Y(neurons_[s.gate.neuron].state) << " - " << P(s.gate.V_h) << ");\n";
    o << "  a[n++] = " << P(s.q.gamma) << " * (" << Y(neurons_[s.pre].state) << " - " << P(s.q.V_h) << ");\n";
  }
  for (size_t mi : c.modulations)
    for (const Condition& cd : modulations_[mi].conditions) {
      if (cd.kind == Condition::AngleBelow)
        o << "  a[n++] = -(" << P(cd.threshold) << " - " << Y(cd.angle_state) << " * " << deg << ") / " << P(cd.width) << ";\n";
      if (cd.kind == Condition::AngleAbove)
        o << "  a[n++] = -(" << Y(cd.angle_state) << " * " << deg << " - " << P(cd.threshold) << ") / " << P(cd.width) << ";\n";
    }
  for (size_t j = 0; j < c.neurons.size(); ++j) {
    const Neuron& nr = neurons_[c.neurons[j]];
    if (!nr.motoneuron) {
      const NapIdx& x = nr.nap;
      const size_t idx[14] = {x.C_m, x.epsilon, x.g_NaP, x.E_Na, x.V_hm, x.gamma_m, x.V_hh,
                              x.gamma_h, x.V_tau_h, x.gamma_tau, x.g_L, x.E_L, x.g_app, x.E_app};
      o << "  const NapNeuronParams<double> q" << j << brace(idx) << ";\n";
      o << "  nap_exp_args(q" << j << ", " << Y(nr.state) << ", a + n);\n  n += kNapExpArgs;\n";
      continue;
    }
    o << "  const MotoneuronParams<double> q" << j << brace(nr.mn.v) << ";\n";
    if (!rate_mn_) o << "  motoneuron_exp_args(q" << j << ", " << Y(nr.state) << ", a + n);\n  n += kMotoneuronExpArgs;\n";
  }
  if (!rate_mn_)
    for (size_t mi : c.muscles)
      o << "  a[n++] = -(" << Y(neurons_[muscles_[mi].motoneuron].state) << " - " << P(act_V_) << ") / " << P(act_w_) << ";\n";
  o << "  ctx->exp_each(a, e, n);\n";
  // Phase 3: currents and drives, neurons, muscles, joints (currents_and_drives, neuron_equations,
  // joint_equations), with the per-neuron sums as locals.
  for (size_t i : c.neurons) o << "  double I_syn" << i << " = 0.0, g_extra" << i << " = 0.0;\n";
  for (size_t i : c.muscles) o << "  double tone" << i << " = 0.0;\n";
  for (size_t si : c.synapses) {
    const Synapse& s = synapses_[si];
    o << "  {\n    double g = " << P(s.q.g) << ";\n";
    if (s.gate.neuron != kNoIndex) o << "    g *= 1.0 - " << P(s.gate.strength) << " * (1.0 / (1.0 + e[k++]));\n";
    o << "    I_syn" << s.post << " += g * (1.0 / (1.0 + e[k++])) * (" << Y(neurons_[s.post].state) << " - " << P(s.q.E) << ");\n  }\n";
  }
  for (size_t mi : c.modulations) {
    const Modulation& m = modulations_[mi];
    o << "  {\n    double gate = 1.0;\n";
    for (const Condition& cd : m.conditions) {
      switch (cd.kind) {
        case Condition::AngleBelow:
        case Condition::AngleAbove: o << "    gate *= 1.0 / (1.0 + e[k++]);\n"; break;
        case Condition::TimeAfter: o << "    if (t < " << P(cd.threshold) << ") gate = 0.0;\n"; break;
        case Condition::TimeBefore: o << "    if (t >= " << P(cd.threshold) << ") gate = 0.0;\n"; break;
      }
    }
    const std::string target = (m.target == Modulation::RestTone ? "tone" : "g_extra") + std::to_string(m.neuron);
    if (m.reference == kNoIndex) o << "    " << target << " += " << P(m.delta) << " * gate;\n  }\n";
    else o << "    " << target << " += (" << P(m.delta) << " - " << P(m.reference) << ") * gate;\n  }\n";
  }
  for (size_t j = 0; j < c.neurons.size(); ++j) {
    const size_t i = c.neurons[j];
    const Neuron& nr = neurons_[i];
    const std::string q = "q" + std::to_string(j), s = std::to_string(nr.state), s1 = std::to_string(nr.state + 1);
    if (!nr.motoneuron) {
      o << "  nap_neuron_rhs(" << q << ", double(" << q << ".g_app + g_extra" << i << "), y[" << s << "], y[" << s1
        << "], I_syn" << i << ", e + k, ydot[" << s << "], ydot[" << s1 << "]);\n  k += kNapExpArgs;\n";
      continue;
    }
    o << "  const double g_app" << i << " = " << q << ".g_app + g_extra" << i << ";\n";
    if (rate_mn_) {
      o << "  const double R" << i << " = motoneuron_rate(y[" << s << "], " << P(rate_.V_th) << ", " << P(rate_.width) << ", "
        << P(rate_.dV_ref) << ", " << P(rate_.exponent) << ");\n";
      o << "  rate_motoneuron_rhs(" << q << ", g_app" << i << ", " << P(rate_.q_max) << ", &y[" << s << "], I_syn" << i
        << ", R" << i << ", &ydot[" << s << "]);\n";
    } else {
      o << "  motoneuron_rhs(" << q << ", g_app" << i << ", &y[" << s << "], I_syn" << i << ", e + k, &ydot[" << s
        << "]);\n  k += kMotoneuronExpArgs;\n";
    }
  }
  for (size_t mi : c.muscles) {
    const Muscle& m = muscles_[mi];
    const std::string a = Y(m.activation), out = "ydot[" + std::to_string(m.activation) + "]";
    if (rate_mn_) {
      o << "  " << out << " = " << P(rate_.gain) << " * R" << m.motoneuron << " * (1.0 - " << a << ") - " << P(act_b_)
        << " * " << a << ";\n";
    } else {
      o << "  {\n    double S = 1.0 / (1.0 + e[k++]);\n    " << out << " = (" << P(act_a0_) << " + " << P(act_b_)
        << ") * S * (1.0 - " << a << ") - " << P(act_b_) << " * (1.0 - S) * " << a << ";\n  }\n";
    }
  }
  for (size_t ji : c.joints) {
    const Joint& j = joints_[ji];
    const Muscle &mi = muscles_[j.muscle_inc], &md = muscles_[j.muscle_dec];
    const std::string ai = Y(mi.activation), ad = Y(md.activation);
    const std::string wi = "tone" + std::to_string(j.muscle_inc), wd = "tone" + std::to_string(j.muscle_dec);
    o << "  {\n    double k_inc = " << P(mi.k_rest) << " + (" << P(mi.k_active) << " - " << P(mi.k_rest) << ") * " << ai
      << " - " << wi << " * " << P(mi.k_rest) << " * (1.0 - " << ai << ") * (1.0 - " << ad << ");\n";
    o << "    double k_dec = " << P(md.k_rest) << " + (" << P(md.k_active) << " - " << P(md.k_rest) << ") * " << ad
      << " - " << wd << " * " << P(md.k_rest) << " * (1.0 - " << ad << ") * (1.0 - " << ai << ");\n";
    o << "    ydot[" << j.angle_state << "] = " << Y(j.velocity_state) << " * 1e-3;\n";
    o << "    ydot[" << j.velocity_state << "] = ctx->joint_acceleration(ctx->model, " << ji << ", p, "
      << Y(j.angle_state) << ", " << Y(j.velocity_state) << ", k_inc, k_dec) * 1e-3;\n  }\n";
  }
  o << "}\n";
  return o.str();
}

double NetworkModel::joint_acceleration_of(const void* model, size_t joint, const double* p, double angle,
                                           double omega, double k_inc, double k_dec) {
  const auto& m = *static_cast<const NetworkModel*>(model);
  return joint_acceleration(m.joints_[joint].mech, p, angle, omega, k_inc, k_dec);
}

}  // namespace phasmid::model
