#include "model/network_builder.hpp"

#include <cmath>

namespace phasmid::model {
namespace {
const char* kA1 = "Knops 2013, Table A.1";
const char* kA2 = "Knops 2013, Table A.2";
const char* kA3 = "Knops 2013, Table A.3";
const char* kA4 = "Knops 2013, Table A.4";
const char* kMN = "Knops 2013, Tables A.5-A.9";
const char* kChoice = "documented choice (docs/model.md)";
constexpr double kInf = INFINITY;

struct Defs {
  NetworkModel& m;
  size_t operator()(const std::string& name, double v, const char* unit, const std::string& src,
                    const std::string& desc, double lo = -kInf, double hi = kInf) {
    return m.define({name, v, unit, src, desc, lo, hi});
  }
};

// Per-joint CPG time constant coefficient and capacitance (Table A.1) and drives (Table A.2).
struct CpgJointValues { double epsilon, C_m, g_app_inc, g_app_dec; };
CpgJointValues cpg_values(JointType t) {
  switch (t) {
    case JointType::Thc: return {0.0019, 1.1493, 0.165, 0.205};  // retractor 0.165, protractor 0.205
    // Levator/depressor: Table A.2 prints 0.230/0.184 nS, which with the CS pathway wired as in
    // Section 2.5.3 (INCS/IN8 excite the depressor CPG, IN7 inhibits the levator CPG) and the
    // V_hh = -44 mV CPG give levation 355 ms : depression 240 ms (wrong way round); 0.34/0.14 nS
    // give 193 : 314 ms (3:5, period 508 ms), grid search (docs/walking_model.md).
    case JointType::Ctr: return {0.0012, 1.8308, 0.34, 0.14};
    case JointType::Fti: return {0.0023, 0.9154, 0.100, 0.209};  // flexor 0.100, extensor 0.209
  }
  return {};
}
}  // namespace

NeuronClasses define_neuron_classes(NetworkModel& m, MotoneuronModel mn_model) {
  Defs def{m};
  NeuronClasses c{};
  // NaP kinetics shared by CPG neurons (Table A.2) and interneurons (Table A.3).
  auto nap_kinetics = [&](const std::string& cls, const char* src, NapIdx& x, double V_hh, const std::string& V_hh_src) {
    x.E_Na = def(cls + ".E_Na", 50, "mV", src, "NaP reversal potential");
    x.V_hm = def(cls + ".V_hm", -37, "mV", src, "NaP activation midpoint");
    x.gamma_m = def(cls + ".gamma_m", -1.0 / 6, "1/mV", src, "NaP activation slope");
    x.V_hh = def(cls + ".V_hh", V_hh, "mV", V_hh_src, "NaP inactivation midpoint");
    x.gamma_h = def(cls + ".gamma_h", 1.0 / 6, "1/mV",
                    std::string(src) + "; sign corrected (printed -1/6 gives an activation curve, docs/model.md)",
                    "NaP inactivation slope (positive: h_inf decreases with V)");
    x.V_tau_h = def(cls + ".V_tau_h", -30, "mV", src, "midpoint of the inactivation rate");
    x.gamma_tau = def(cls + ".gamma_tau", -1.0 / 12, "1/mV", src, "slope of the inactivation rate");
    x.E_L = def(cls + ".E_L", -65, "mV", src, "leak reversal potential");
  };
  // With the printed V_hh = -30 mV the active half-centre neuron has a stable fixed point near
  // -21 mV and never releases; -44 mV gives a 512.5 ms half-centre rhythm with the Table A.1/A.2
  // values of the FE CPG (grid search with phasmid, docs/model.md).
  nap_kinetics("cpg", kA2, c.cpg_shared, -44.0,
               "Table A.2 prints -30 mV (no rhythm); -44 mV tuned to the 510 ms period (docs/model.md)");
  c.cpg_shared.g_NaP = def("cpg.g_NaP", 10, "nS", kA2, "NaP conductance of CPG neurons", 0);
  c.cpg_shared.g_L = def("cpg.g_L", 2.8, "nS", kA2, "leak conductance of CPG neurons", 0);
  c.cpg_shared.E_app = def("cpg.E_app", 0, "mV", kA2, "reversal of the central drive");

  NapIdx in_base{};
  nap_kinetics("interneuron", kA3, in_base, -30.0, kA3);
  in_base.epsilon = def("interneuron.epsilon", 0.010, "1/ms", kA1, "inactivation time constant coefficient", 0);
  in_base.C_m = def("interneuron.C_m", 0.210, "pF", kA1, "membrane capacitance of interneurons", 1e-6);
  c.in_mn = c.sens_inh = c.sens_exc = c.sens_exc_ld = in_base;
  c.in_mn.g_NaP = def("interneuron.to_mn.g_NaP", 10, "nS", kA3, "NaP conductance of the inhibitory INs to MNs", 0);
  c.in_mn.g_L = def("interneuron.to_mn.g_L", 2.8, "nS", kA3, "leak of the inhibitory INs to MNs", 0);
  c.in_mn.E_app = def("interneuron.inhibitory.E_app", -80, "mV", kA3, "drive reversal of inhibitory INs");
  c.sens_inh.g_NaP = def("interneuron.sens_inh.g_NaP", 10, "nS", kA3, "NaP of inhibitory peripheral INs", 0);
  c.sens_inh.g_L = def("interneuron.sens_inh.g_L", 6.8, "nS", kA3, "leak of inhibitory peripheral INs", 0);
  c.sens_inh.E_app = c.in_mn.E_app;
  c.sens_exc.g_NaP = def("interneuron.sens_exc.g_NaP", 5, "nS", kA3, "NaP of excitatory peripheral INs (PR, FE)", 0);
  c.sens_exc.g_L = def("interneuron.sens_exc.g_L", 10, "nS", kA3, "leak of excitatory peripheral INs (PR, FE)", 0);
  c.sens_exc.E_app = def("interneuron.excitatory.E_app", 0, "mV", kA3, "drive reversal of excitatory INs");
  c.sens_exc_ld.g_NaP = def("interneuron.sens_exc_ld.g_NaP", 7, "nS", kA3, "NaP of excitatory peripheral INs (LD)", 0);
  c.sens_exc_ld.g_L = def("interneuron.sens_exc_ld.g_L", 9.85, "nS", kA3, "leak of excitatory peripheral INs (LD)", 0);
  c.sens_exc_ld.E_app = c.sens_exc.E_app;

  // Motoneurons, Tables A.5-A.9 (same order as MotoneuronParams).
  struct V { const char* n; double v; const char* u; const char* d; };
  const V mn[32] = {
      {"C_m", 1.0, "pF", "membrane capacitance"}, {"g_Na", 10, "nS", "Na conductance (printed g_NaP)"},
      {"E_Na", 55, "mV", "Na reversal"}, {"Na.a_m1", 0.32, "1/(ms*mV)", "alpha_m scale (2.10)"},
      {"Na.a_m2", -51.9, "mV", "alpha_m offset"}, {"Na.a_m3", 0.25, "1/mV", "alpha_m slope"},
      {"Na.b_m1", -0.28, "1/(ms*mV)", "beta_m scale (2.11)"}, {"Na.b_m2", -24.9, "mV", "beta_m offset"},
      {"Na.b_m3", -0.20, "1/mV", "beta_m slope"}, {"Na.a_h1", 0.128, "1/ms", "alpha_h scale (2.12)"},
      {"Na.a_h2", -48.0, "mV", "alpha_h offset"}, {"Na.a_h3", 0.056, "1/mV", "alpha_h slope"},
      {"Na.b_h1", 4.0, "1/ms", "beta_h scale (2.13)"}, {"Na.b_h2", -25.0, "mV", "beta_h offset"},
      {"Na.b_h3", 0.20, "1/mV", "beta_h slope"}, {"g_K", 2, "nS", "K conductance"},
      {"E_K", -80, "mV", "K reversal"}, {"K.a_m1", 0.016, "1/(ms*mV)", "alpha_mK scale (2.14)"},
      {"K.a_m2", -29.9, "mV", "alpha_mK offset"}, {"K.a_m3", 0.20, "1/mV", "alpha_mK slope"},
      {"K.b_m1", 0.25, "1/ms", "beta_mK scale (2.15)"}, {"K.b_m2", -45.0, "mV", "beta_mK offset"},
      {"K.b_m3", 0.025, "1/mV", "beta_mK slope"}, {"g_q", 12, "nS", "adaptation conductance"},
      {"E_q", -80, "mV", "adaptation reversal: printed +12 mV makes the 'outward (potassium)' current depolarising and drives MNs into block; -80 mV = E_K (docs/model.md)"}, {"V_hq", -30, "mV", "m_q midpoint"},
      {"s_q", -0.6, "1/mV", "m_q slope"}, {"r_q", 0.0005, "1/ms", "adaptation rate (2.18)"},
      {"g_L", 0.8, "nS", "leak"}, {"E_L", -70.0, "mV", "leak reversal"},
      {"g_app", 0.40, "nS", "tonic drive g_MN; Table A.9 prints 0.19 nS, which gives too sparse firing for full joint excursions; 0.40 nS by grid search (docs/model.md)"}, {"E_app", 0, "mV", "drive reversal"}};
  for (int k = 0; k < 32; ++k) c.mn.v[k] = def(std::string("mn.") + mn[k].n, mn[k].v, mn[k].u, kMN, mn[k].d);

  auto syn = [&](const std::string& cls, double g, double V_h, double gamma, double E, const std::string& what) {
    SynapseIdx s;
    s.g = def("syn." + cls + ".g", g, "nS", kA4, "maximal conductance, " + what, 0);
    s.V_h = def("syn." + cls + ".V_h", V_h, "mV", kA4, "half-activation of s_inf, " + what);
    s.gamma = def("syn." + cls + ".gamma", gamma, "1/mV", kA4, "slope of s_inf, " + what);
    s.E = def("syn." + cls + ".E", E, "mV", kA4, "reversal, " + what);
    return s;
  };
  c.cpg_cpg = syn("cpg_cpg", 1.0, -43, -10, -80, "CPG to CPG (mutual inhibition)");
  c.in_cpg_inh = syn("in_cpg_inh", 0.05, -43, -10, -80, "inhibitory IN to CPG");
  c.in_cpg_exc = syn("in_cpg_exc", 0.1, -43, -0.42, 0, "excitatory IN to CPG");
  c.in_mn_syn = syn("in_mn", 0.25, -43, -0.1, -80, "inhibitory IN to MN");
  c.cpg_in = syn("cpg_in", 0.5, -43, -10, 0, "excitatory CPG to IN");

  size_t a0 = def("muscle.a0", 2.0, "1/ms", kChoice, "activation rate during an action potential (2.83), a0 >> b", 0);
  size_t b = def("muscle.b", 0.02, "1/ms", "documented choice, grid search for the 45-110 deg FTi range (docs/model.md)", "relaxation rate of the spring constant (2.84)", 0);
  size_t Vs = def("muscle.V_spike", -20, "mV", kChoice, "MN voltage above which an action potential is counted");
  size_t w = def("muscle.spike_width", 2.0, "mV", kChoice, "width of the smooth spike criterion", 1e-6);
  m.set_muscle_activation_params(a0, b, Vs, w);
  if (mn_model == MotoneuronModel::Rate) {
    // Rate formulation (docs/model.md, "Rate motoneurons"): R(V) is the f-V relation of the
    // Traub MN above (tonic firing at frozen m_q = 0.045 vs the passive potential, 100 Hz =
    // R 1), q_max and gain the spike averages of (2.16) and (2.83)/(2.84) at that rate. The
    // onset, its smoothing, the exponent and the gain are then calibrated on the spiking middle
    // leg and tetrapod together (the network approaches threshold differently from a constant
    // drive); V_th, width and gain stay at their f-V values, the exponent halves.
    const char* kFV = "f-V curve of the spiking MN, scripts/rate_mn_fv.py (docs/model.md)";
    const char* kFit = "joint fit to the spiking middle leg and tetrapod, scripts/rate_mn_joint_fit.py (docs/model.md)";
    RateMotoneuronIdx r;
    r.V_th = def("mn.rate.V_th", -59.12, "mV", kFit, "onset of repetitive firing of a rate MN (passive potential; f-V curve: -59.19 mV)", -70, -30);
    r.width = def("mn.rate.width", 0.0005, "mV", kFit, "smoothing of the firing onset (softplus width; f-V curve: < 0.001 mV)", 0.0005, 10);
    r.dV_ref = def("mn.rate.dV_ref", 2.149, "mV", kFV, "depolarisation above the onset at which the MN fires at f_ref = 100 Hz (R = 1)", 0.1, 20);
    r.exponent = def("mn.rate.exponent", 0.197055, "1", kFit, "exponent of the f-V relation R = (softplus(V - V_th)/dV_ref)^p (f-V curve: 0.37)", 0.05, 2);
    r.q_max = def("mn.rate.q_max", 0.095, "1", kFV,
                  "adaptation drive at f_ref: mean of m_q,inf(V) during tonic firing at 100 Hz (dm_q/dt = r_q (q_max R - m_q))", 0, 1);
    r.gain = def("muscle.rate.gain", 0.133599, "1/ms", kFit,
                 "muscle activation rate at f_ref (spike average of (2.83)/(2.84): da/dt = gain R (1 - a) - b a; f-V curve: 0.13)", 0, 10);
    m.set_rate_motoneurons(r);
  }
  return c;
}

JointNetwork add_joint_network(NetworkModel& m, const NeuronClasses& c, const std::string& leg, JointType type,
                               double angle0_deg, const std::string& thc_set, CpgToIn wiring) {
  Defs def{m};
  JointNaming nm = joint_naming(type);
  JointNetwork jn;
  jn.prefix = leg + "." + joint_name(type);
  const std::string pre = jn.prefix + ".";
  CpgJointValues cv = cpg_values(type);
  NapIdx cpg = c.cpg_shared;
  cpg.epsilon = def(pre + "cpg.epsilon", cv.epsilon, "1/ms", kA1, "CPG inactivation time constant coefficient", 0);
  cpg.C_m = def(pre + "cpg.C_m", cv.C_m, "pF", kA1, "CPG membrane capacitance", 1e-6);

  auto nap = [&](const std::string& name, NapIdx q, double g_app, const char* src, const std::string& desc,
                 double V0, double h0) {
    q.g_app = def(pre + name + ".g_app", g_app, "nS", src, desc, 0);
    return m.add_nap_neuron(pre + name, q, V0, h0);
  };
  const std::string inc = nm.muscle_inc, dec = nm.muscle_dec;
  const char* drive_src = type == JointType::Ctr
                              ? "Table A.2 prints 0.230 (lev) / 0.184 (dep) nS; retuned to the LD 3:5 phase relation and "
                                "510 ms with the CS pathway of Section 2.5.3 (docs/walking_model.md)"
                              : kA2;
  jn.cpg_inc = nap("cpg_" + inc, cpg, cv.g_app_inc, drive_src, "central drive to the " + inc + " CPG neuron", -60, 0.6);
  jn.cpg_dec = nap("cpg_" + dec, cpg, cv.g_app_dec, drive_src, "central drive to the " + dec + " CPG neuron", -30, 0.3);
  // in_<m> inhibits the motoneuron of muscle m and is excited by the antagonist's CPG (g_d).
  jn.in_inc = nap("in_" + inc, c.in_mn, 1.6, kA3, "drive g_d of the IN inhibiting the " + inc + " MN", -70, 0.9);
  jn.in_dec = nap("in_" + dec, c.in_mn, 1.6, kA3, "drive g_d of the IN inhibiting the " + dec + " MN", -70, 0.9);
  bool ld = type == JointType::Ctr;
  jn.sens_exc = nap("sens_exc", ld ? c.sens_exc_ld : c.sens_exc, ld ? 0.29 : 0.60,
                    ld ? "Knops 2013, Section 3.2 (g_app,CS before the transient)" : "Knops 2013, Section 3.2 (no sensory input)",
                    "drive of the excitatory sensory IN (IN4 / INCS / IN12)", -70, 0.9);
  // IN3 / IN7 / IN11 are Table A.3's "inhibitory peripheral neurons" (g_app = 0.0 nS) and also
  // the walking network's only "inhibitory INs to CPG" (2.0 nS, E_app = -80 mV). 2.0 nS: with
  // it IN11 still has its NaP plateau but drops off it when IN12 falls, so the FE system locks
  // to LD for g_in12_in11 = 1.4-10 nS in the middle leg and also in the tetrapod front leg
  // (0.0 nS: 0.35-0.5 nS, front leg creeping); docs/walking_model.md, "Sensory interneurons".
  jn.sens_inh = nap("sens_inh", c.sens_inh, 2.0,
                    "Knops 2013, Table A.3 ('All inhibitory INs to CPG'; the row 'Inhibitory peripheral neurons' gives 0.0 nS, docs/walking_model.md)",
                    "drive g_app (at E_app = -80 mV) of the inhibitory sensory IN (IN3 / IN7 / IN11)", -70, 0.9);
  jn.mn_inc = m.add_motoneuron(pre + "mn_" + inc, c.mn);
  jn.mn_dec = m.add_motoneuron(pre + "mn_" + dec, c.mn);

  m.add_synapse(jn.cpg_inc, jn.cpg_dec, c.cpg_cpg);
  m.add_synapse(jn.cpg_dec, jn.cpg_inc, c.cpg_cpg);
  if (wiring != CpgToIn::Crossed) {
    jn.syn_par_dec = m.add_synapse(jn.cpg_dec, jn.in_inc, c.cpg_in);  // dec CPG active -> inc MN inhibited
    jn.syn_par_inc = m.add_synapse(jn.cpg_inc, jn.in_dec, c.cpg_in);
  }
  if (wiring != CpgToIn::Parallel) {
    jn.syn_crs_dec = m.add_synapse(jn.cpg_dec, jn.in_dec, c.cpg_in);  // dec CPG active -> dec MN inhibited
    jn.syn_crs_inc = m.add_synapse(jn.cpg_inc, jn.in_inc, c.cpg_in);
  }
  m.add_synapse(jn.in_inc, jn.mn_inc, c.in_mn_syn);
  m.add_synapse(jn.in_dec, jn.mn_dec, c.in_mn_syn);
  // PR and FE: the sensory pathway excites the retractor / flexor CPG (inc) and inhibits the
  // protractor / extensor CPG. LD: the CS pathway excites the depressor CPG C4 via IN8 and
  // inhibits the levator CPG C3 via IN7 (Section 2.5.3), i.e. the dec side.
  const size_t excited = ld ? jn.cpg_dec : jn.cpg_inc, inhibited = ld ? jn.cpg_inc : jn.cpg_dec;
  m.add_synapse(jn.sens_exc, excited, c.in_cpg_exc);
  jn.syn_sens = m.add_synapse(jn.sens_exc, jn.sens_inh, c.in_cpg_exc);  // IN3 "is excited by IN4" (Fig. 2.12)
  m.add_synapse(jn.sens_inh, inhibited, c.in_cpg_inh);

  JointMechanics mech = define_joint_mechanics(m.parameters(), leg, type, thc_set);
  size_t mus_inc = m.add_muscle(jn.mn_inc, mech.k_inc_in_dec, mech.k_inc_in_inc, pre + inc);
  size_t mus_dec = m.add_muscle(jn.mn_dec, mech.k_dec_in_inc, mech.k_dec_in_dec, pre + dec);
  jn.joint = m.add_joint(leg, mech, mus_inc, mus_dec, angle0_deg);
  return jn;
}

std::unique_ptr<NetworkModel> build_single_joint_model(const std::string& leg, JointType type,
                                                       const std::string& thc_set, MotoneuronModel mn) {
  auto m = std::make_unique<NetworkModel>("single_joint");
  NeuronClasses c = define_neuron_classes(*m, mn);
  JointTable t = joint_table(leg, type, thc_set);
  add_joint_network(*m, c, leg, type, 0.5 * (t.angle_min_deg + t.angle_max_deg), thc_set);
  return m;
}

}  // namespace phasmid::model
