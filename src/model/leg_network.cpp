#include "model/leg_network.hpp"

#include <cmath>

#include "common/error.hpp"

namespace phasmid::model {

void LegOptions::hold_until(double start_ms) {
  ld_release_ms = start_ms;
  ld_release_source = "config start_ms (a choice: the seeds give no start phase of the single leg)";
  ld_hold_g_pr = 5.0;
  ld_hold_g_pr_source = "choice: PR silent until the start time, as in curve walking (Section 2.5.3: the PR is a reflex chain)";
}
namespace {
const char* k32 = "Knops 2013, Section 3.2";
const char* k322 = "Knops 2013, Section 3.2.2 / Fig. 3.11 (Toth et al. 2012); strength a documented choice (docs/walking_model.md)";
const char* kChoice = "documented choice (docs/walking_model.md)";
constexpr double kNever = 1e9;  // ms: a command time beyond any simulation (command off)

struct Def {
  NetworkModel& m;
  size_t operator()(const std::string& name, double v, const char* unit, const std::string& src,
                    const std::string& desc, double lo = -INFINITY, double hi = INFINITY) {
    return m.define({name, v, unit, src, desc, lo, hi});
  }
  // Network-level parameters shared by several legs: defined by the first leg.
  size_t once(const std::string& name, double v, const char* unit, const std::string& src, const std::string& desc,
              double lo = -INFINITY, double hi = INFINITY) {
    if (m.parameters().contains(name)) return m.parameters().index(name);
    return (*this)(name, v, unit, src, desc, lo, hi);
  }
};

// Synapse class of the central command neurons (sideward stop, levator hold), shared by all
// legs and defined by the first that needs it.
SynapseIdx command_inhibition_synapse(Def& def) {
  const std::string cls = "syn.command_inh.";
  const std::string as_a4 = std::string(kChoice) + ": as Table A.4";
  return {def.once(cls + "g", 5.0, "nS", kChoice, "inhibition by central command neurons (sideward stop: SF, SB and the PR MNs; levator hold)", 0),
          def.once(cls + "V_h", -43, "mV", as_a4, "half-activation"),
          def.once(cls + "gamma", -10, "1/mV", as_a4, "slope"),
          def.once(cls + "E", -80, "mV", as_a4, "reversal (inhibitory)")};
}

Condition below(size_t state, size_t thr, size_t width) { return {Condition::AngleBelow, state, thr, width}; }
Condition above(size_t state, size_t thr, size_t width) { return {Condition::AngleAbove, state, thr, width}; }
Condition after(size_t t) { return {Condition::TimeAfter, 0, t, 0}; }
Condition before(size_t t) { return {Condition::TimeBefore, 0, t, 0}; }

// The sensory couplings of one leg (Section 3.2): ground contact (beta) and the fCO (gamma)
// gate the sensory IN drives, the CS input switches the LD system on, and the IN -> IN
// excitations carry the sensory INs' activity on.
void add_sensory_coupling(NetworkModel& m, const NeuronClasses& c, Def& def, LegNetwork& L, const LegOptions& o) {
  const std::string& leg = L.leg;
  const std::string pre = leg + ".coupling.";
  L.beta_thr_pr = def(pre + "beta_thr_pr", 38, "deg", k32, "beta below this: ground contact, PR sensory IN excited");
  // The retractor CPG (Figs. 3.20-3.22 plot it against beta) counts as active above the
  // half-activation of the CPG -> IN synapse, the level at which it drives its pathway.
  m.add_contact_leg({leg, L.beta_state, L.beta_thr_pr, m.neurons()[L.pr.cpg_inc].state, c.cpg_in.V_h});
  size_t beta_fe = def(pre + "beta_thr_fe", 50, "deg", k32, "beta below this: FE sensory IN (IN12) excited");
  size_t gamma_thr = def(pre + "gamma_thr", 90, "deg", k32, "gamma above this during ground contact: IN12 reduced (fCO)");
  L.width = def(pre + "width_deg", 1.0, "deg",
                "documented choice: smooth threshold width (docs/model.md, docs/walking_model.md)",
                "width of the sigmoid replacing the angle thresholds", 1e-6);
  // The PR/FE sensory IN base drives are the joint networks' sens_exc.g_app (0.60 nS);
  // in the three-leg model the PR one is IN16's 1.6 nS (Section 3.3).
  size_t pr_base = m.parameters().index(leg + ".thc.sens_exc.g_app");
  m.parameters().set(pr_base, o.g_pr_swing);
  size_t fe_base = m.parameters().index(leg + ".fti.sens_exc.g_app");
  size_t cs_base = m.parameters().index(leg + ".ctr.sens_exc.g_app");
  size_t g_pr = def(pre + "g_pr_stance", o.g_pr_stance, "nS", o.g_pr_source,
                    "drive of the PR sensory IN (IN4 / IN16) during ground contact", 0);
  size_t g_fe = def(pre + "g_fe_stance", 3.00, "nS", k32, "drive of IN12 during ground contact (beta < beta_thr_fe)", 0);
  size_t g_fco = def(pre + "g_fe_fco", 1.90, "nS", k32, "drive of IN12 during ground contact with gamma > gamma_thr", 0);
  size_t g_cs = def(pre + "g_cs_on", 2.00, "nS", k32, "drive of INCS after the initial transient (LD oscillates)", 0);
  size_t cs_on = def(pre + "cs_on_ms", o.cs_on_ms, "ms",
                     o.cs_on_source.empty() ? std::string(kChoice) + ": end of the 'short transient' of Section 3.2"
                                            : o.cs_on_source,
                     "time at which the CS input to the LD system is switched on (LD start time)", 0);
  // Each Modulation is the (smooth) product of its conditions.
  m.add_modulation({L.pr.sens_exc, g_pr, {below(L.beta_state, L.beta_thr_pr, L.width)}, pr_base});
  m.add_modulation({L.fe.sens_exc, g_fe, {below(L.beta_state, beta_fe, L.width)}, fe_base});
  m.add_modulation({L.fe.sens_exc, g_fco, {below(L.beta_state, beta_fe, L.width), above(L.gamma_state, gamma_thr, L.width)}, g_fe});
  m.add_modulation({L.ld.sens_exc, g_cs, {after(cs_on)}, cs_base});
  // Slope of the IN -> IN synapses (IN4 -> IN3, INCS -> IN7, IN12 -> IN11), shared by all legs.
  const size_t in_in_gamma = def.once("syn.in_in.gamma", -0.42, "1/mV",
                                      std::string(kChoice) + ": Table A.4 lists no IN -> IN class; slope of its excitatory IN -> CPG class (the presynaptic IN type; -10 of the CPG -> IN class unlocks the FE system at 0.5 nS)",
                                      "slope of s_inf of the IN -> IN excitation (IN3, IN7, IN11 excited by IN4, INCS, IN12)");
  // The IN -> IN excitations (Table A.4 lists no class for them): the excitatory IN -> CPG
  // class with the IN -> IN slope and a conductance of their own.
  auto set_in_in = [&](size_t synapse, const char* name, double g_nS, const std::string& source, const char* what) {
    SynapseIdx q = c.in_cpg_exc;
    q.gamma = in_in_gamma;
    q.g = def(pre + name, g_nS, "nS", source, what, 0);
    m.set_synapse_params(synapse, q);
  };
  // IN12 -> IN11 (FE system, Fig. 2.13: IN11 "is excited by" IN12 and inhibits the extensor
  // CPG C5, Section 2.5.3). Table A.4 lists no class for this synapse; with the excitatory
  // IN -> CPG class (0.1 nS) IN11 stays at rest and the FE system is not entrained by beta.
  // With IN11's drive of 2.0 nS (Table A.3) it needs > 1.33 nS to leave rest; 2.0 nS locks FE
  // to LD in all legs (docs/walking_model.md, "FE entrainment", "Sensory interneurons").
  set_in_in(L.fe.syn_sens, "g_in12_in11", 2.0,
            std::string(kChoice) + ": Table A.4 lists no IN -> IN class; with IN11's Table A.3 drive of 2.0 nS the FE system locks 1:1 to LD for 1.4-10 nS (scan)",
            "maximal conductance of the IN12 -> IN11 excitation (otherwise the excitatory IN -> CPG class of Table A.4)");
  // IN4 -> IN3 (PR): IN3 "is excited by IN4" and inhibits the protractor CPG (Sections 2.5.1,
  // 2.5.3). The same unlisted IN -> IN synapse as IN12 -> IN11, so the same 2.0 nS: IN3 then
  // follows IN4 (on its NaP plateau while IN4 is raised in ground contact, at rest in the
  // swing), the gait is unchanged. With 0.1 nS IN3 stays at rest; docs/walking_model.md,
  // "Sensory interneurons IN3, IN7, IN11".
  set_in_in(L.pr.syn_sens, "g_in4_in3", 2.0,
            std::string(kChoice) + ": Table A.4 lists no IN -> IN class; as g_in12_in11 (IN3 follows IN4)",
            "maximal conductance of the IN4 (IN16) -> IN3 excitation (PR system)");
  // INCS -> IN7 (LD): kept at the excitatory IN -> CPG class's 0.1 nS, with which IN7 stays at
  // rest. The CS input is tonic while walking (2.00 nS), so an excited IN7 is a tonic inhibition
  // of the levator CPG: with 0.5 nS (IN7 drive 0.0 nS) IN7 sits on its plateau throughout, the
  // LD period becomes 522 ms and the FE system unlocks; the LD drives (0.34 / 0.14 nS,
  // docs/walking_model.md) were tuned without it.
  set_in_in(L.ld.syn_sens, "g_incs_in7", 0.1,
            std::string(kChoice) + ": Table A.4 lists no IN -> IN class; its excitatory IN -> CPG value (0.5 nS: tonic IN7, LD 522 ms)",
            "maximal conductance of the INCS -> IN7 excitation (LD system)");
}

// The central levator hold that starts the leg at o.ld_release_ms (Section 2.5.4), and the
// hold and release commands of gait transitions (Section 3.3).
void add_levator_hold(NetworkModel& m, const NeuronClasses& c, Def& def, const LegNetwork& L, const LegOptions& o) {
  const std::string& leg = L.leg;
  // "central inhibition of the levator CPG neuron in the respective leg, i.e. forcing the
  // depressor CPG neuron to be active and then resetting the CPG at proper times" (2.5.4).
  const std::string h = leg + ".ld_hold.";
  NapIdx q = c.sens_inh;
  q.E_app = m.parameters().index("interneuron.excitatory.E_app");
  size_t drive = def(h + "drive", 5.0, "nS", kChoice, "central drive of the levator-inhibiting command neuron while holding", 0);
  size_t zero = def(h + "off", 0.0, "nS", kChoice, "its drive when released", 0);
  q.g_app = drive;
  size_t hold = m.add_nap_neuron(leg + ".ld_hold", q, -30, 0.3);
  SynapseIdx si = command_inhibition_synapse(def);
  m.add_synapse(hold, L.ld.cpg_inc, si);
  if (o.ld_hold_g_pr > 0) {
    // The PR system is a reflex chain, "not active in the absence of the (excitatory)
    // peripheral input" (Section 2.5.3), but phasmid's PR CPG oscillates on its own (633 ms
    // at IN4 = 0.60 nS) and, with the held leg at beta ~ 40 deg (just above beta_thr_pr),
    // would run freely through the hold: its phase at the release would depend on the release
    // time, and a leg released in the PR's protraction phase would retract during its first
    // swing, protract during its first stance and need up to four more steps to retract in
    // stance (an apparent "second locking" of curve walking). The hold neuron therefore
    // silences both PR CPGs until the leg's start time, so every leg starts its PR from the
    // same state. docs/walking_model.md, "Curve walking".
    SynapseIdx sp = si;
    sp.g = def(h + "g_pr", o.ld_hold_g_pr, "nS",
               o.ld_hold_g_pr_source.empty() ? std::string(kChoice) : o.ld_hold_g_pr_source,
               "inhibition of both PR CPGs (retractor, protractor) by the levator-hold command neuron", 0);
    m.add_synapse(hold, L.pr.cpg_inc, sp);
    m.add_synapse(hold, L.pr.cpg_dec, sp);
  }
  size_t rel = def(leg + ".command.ld_release_ms", o.ld_release_ms, "ms",
                   o.ld_release_source.empty() ? std::string(kChoice) : o.ld_release_source,
                   "end of the central levator inhibition: the leg's first lift-off (start time)", 0);
  size_t hold2 = def(leg + ".command.ld_hold_ms", kNever, "ms", "Knops 2013, Section 3.3 / Figs. 3.24-3.27",
                     "gait transition: central levator inhibition starts again (after ld_release_ms)", 0);
  size_t rel2 = def(leg + ".command.ld_release2_ms", kNever, "ms", "Knops 2013, Section 3.3 / Figs. 3.24-3.27",
                    "gait transition: levator released again (reset; after ld_hold_ms)", 0);
  m.add_modulation({hold, zero, {after(rel)}, drive});
  m.add_modulation({hold, drive, {after(hold2)}, zero});
  m.add_modulation({hold, zero, {after(rel2)}, drive});
  // "The levator ... is suppressed" (Section 3.3) during a gait-transition hold: inhibiting
  // the levator CPG alone keeps the levator MN silent only through IN inhibition, from which
  // it escapes after ~300 ms as its adaptation (m_q, r_q = 0.0005/ms) decays; the tripod ->
  // tetrapod protocol holds the front leg for ~600 ms. So the levator MN's tonic drive is
  // lowered to ld_hold.g_mn_lev from ld_hold_ms to ld_release2_ms (the start-time hold from
  // t = 0 is unchanged). docs/walking_model.md, "Gait transitions".
  size_t g_mn = m.parameters().index("mn.g_app");
  size_t mn_held = def(h + "g_mn_lev", 0.0, "nS",
                       std::string(kChoice) + ": levator MN silent for the whole transition hold (Section 3.3)",
                       "tonic drive of the levator MN during a gait-transition hold (ld_hold_ms to ld_release2_ms)", 0);
  m.add_modulation({L.ld.mn_inc, mn_held, {after(hold2)}, g_mn});
  m.add_modulation({L.ld.mn_inc, g_mn, {after(rel2)}, mn_held});
  // "Forcing the depressor CPG neuron to be active" (Section 2.5.4): without levator
  // inhibition the depressor CPG ends its burst by its own NaP inactivation after ~500 ms and
  // bursts again, so a long hold released near such a new burst co-activates both CPGs (a
  // ~560 ms levation). An extra depressor CPG drive while held keeps it active until the reset.
  size_t dep_extra = def(h + "g_cpg_dep", 0.3, "nS",
                         std::string(kChoice) + ": depressor CPG kept active through the transition hold (Section 2.5.4)",
                         "extra drive of the depressor CPG during a gait-transition hold (ld_hold_ms to ld_release2_ms)", 0);
  m.add_modulation({L.ld.cpg_dec, dep_extra, {after(hold2)}});
  m.add_modulation({L.ld.cpg_dec, zero, {after(rel2)}, dep_extra});
}

// The direction switch (Fig. 3.11): command neurons SF and SB, and the central commands of
// backward, forward and sideward stepping (Section 3.2.2).
void add_direction_switch(NetworkModel& m, const NeuronClasses& c, Def& def, LegNetwork& L) {
  const std::string& leg = L.leg;
  // Fig. 3.11: SF and SB, a mutually inhibitory pair driven centrally. SF presynaptically
  // inhibits the crossed CPG -> IN connections of the PR system, SB the parallel ones.
  const std::string sw = leg + ".switch.";
  // Command neurons: NaP interneurons with the leak of the inhibitory peripheral INs (Table
  // A.3, g_L = 6.8 nS), which rest near -65 mV without drive (with g_L = 2.8 nS the NaP
  // current alone holds a plateau, so an undriven neuron would not stay silent).
  NapIdx q = c.sens_inh;
  q.E_app = m.parameters().index("interneuron.excitatory.E_app");
  size_t drive = def(sw + "drive", 5.0, "nS", kChoice, "central drive of the active command neuron (SF or SB)", 0);
  q.g_app = drive;
  L.sf = m.add_nap_neuron(leg + ".switch.sf", q, -30, 0.3);
  size_t sb_g = def(sw + "sb.g_app", 0.0, "nS", kChoice, "central drive of SB at the start (forward walking)", 0);
  q.g_app = sb_g;
  L.sb = m.add_nap_neuron(leg + ".switch.sb", q, -65, 0.9);
  m.add_synapse(L.sf, L.sb, c.cpg_cpg);
  m.add_synapse(L.sb, L.sf, c.cpg_cpg);
  PresynapticGate g;
  g.strength = def.once("syn.presyn.strength", 1.0, "1", k322, "fraction of the CPG -> IN conductance removed by full presynaptic inhibition", 0, 1);
  g.V_h = def.once("syn.presyn.V_h", -43, "mV", std::string(kChoice) + ": as the synapses of Table A.4", "half-activation of presynaptic inhibition");
  g.gamma = def.once("syn.presyn.gamma", -10, "1/mV", std::string(kChoice) + ": as the CPG synapses of Table A.4", "slope of presynaptic inhibition");
  g.neuron = L.sb;
  m.set_synapse_gate(L.pr.syn_par_inc, g);
  m.set_synapse_gate(L.pr.syn_par_dec, g);
  g.neuron = L.sf;
  m.set_synapse_gate(L.pr.syn_crs_inc, g);
  m.set_synapse_gate(L.pr.syn_crs_dec, g);
  // Central commands (Section 3.2.2): steps of the command drives at given times.
  size_t zero = def(sw + "off", 0.0, "nS", kChoice, "drive of an inhibited command neuron", 0);
  size_t t_bwd = def(leg + ".command.backward_ms", kNever, "ms", "Knops 2013, Fig. 3.10 (6000 ms in middle_leg_switch.toml)",
                     "central command: switch to backward stepping (SF off, SB on)", 0);
  size_t t_fwd = def(leg + ".command.forward_ms", kNever, "ms", "Knops 2013, Fig. 3.10 (9250 ms in middle_leg_switch.toml)",
                     "central command: back to forward stepping after backward_ms (SB off, SF on)", 0);
  size_t t_side = def(leg + ".command.sideward_ms", kNever, "ms", "Knops 2013, Fig. 3.12 (4690 ms; middle_leg_sideward.toml starts the leg at 180 ms so that it falls at the phase that gives 102 deg here: docs/walking_model.md)",
                      "central command: sideward stepping (SF and SB inhibited, FE drives changed)", 0);
  m.add_modulation({L.sf, zero, {after(t_bwd)}, drive});
  m.add_modulation({L.sb, drive, {after(t_bwd)}, zero});
  m.add_modulation({L.sf, drive, {after(t_fwd)}, zero});
  m.add_modulation({L.sb, zero, {after(t_fwd)}, drive});
  // Sideward: "simultaneous inhibition of both the neurons SF and SB" (Section 3.2.2) by a
  // centrally driven inhibitory neuron (removing SF's drive alone lets SB rebound and hold).
  q.g_app = zero;
  size_t stop = m.add_nap_neuron(leg + ".switch.stop", q, -65, 0.9);
  SynapseIdx si = command_inhibition_synapse(def);
  m.add_synapse(stop, L.sf, si);
  m.add_synapse(stop, L.sb, si);
  // "Both interneurons are active and both motoneurons are inhibited" (Section 3.2.2): with
  // g_MN = 0.40 nS (docs/model.md) the 0.25 nS IN -> MN inhibition does not keep the PR MNs
  // silent through the CPG switches, so the command neuron also inhibits them directly.
  m.add_synapse(stop, L.pr.mn_inc, si);
  m.add_synapse(stop, L.pr.mn_dec, si);
  m.add_modulation({stop, drive, {after(t_side)}, zero});
  m.add_modulation({L.sf, zero, {after(t_side)}, drive});  // and SF's central drive ends
  size_t ext = m.parameters().index(leg + ".fti.cpg_ext.g_app");
  size_t flx = m.parameters().index(leg + ".fti.cpg_flx.g_app");
  size_t s_ext = def(leg + ".sideward.g_app_ext", 0.190, "nS", "Knops 2013, Section 3.1.2 / Fig. 3.4", "extensor CPG drive during sideward stepping", 0);
  size_t s_flx = def(leg + ".sideward.g_app_flx", 0.120, "nS", "Knops 2013, Section 3.1.2 / Fig. 3.4", "flexor CPG drive during sideward stepping", 0);
  m.add_modulation({L.fe.cpg_dec, s_ext, {after(t_side)}, ext});
  m.add_modulation({L.fe.cpg_inc, s_flx, {after(t_side)}, flx});
  // End of sideward stepping (curve walking, Section 3.2.3): everything back to forward.
  size_t t_side_end = def(leg + ".command.sideward_end_ms", kNever, "ms", "Knops 2013, Section 3.2.3 (curve walking)",
                          "central command: back to forward stepping after sideward_ms", 0);
  m.add_modulation({stop, zero, {after(t_side_end)}, drive});
  // With both PR motoneurons silent, both ThC spring constants decay to 0 with the same rate
  // b as in (2.84), keeping k_R/k_P and hence the angle reached at the command (the
  // fixation angles 28, 102, 128 deg of Section 3.2.2): release of the resting spring
  // constants (see Muscle in network_model.hpp) from the command to its end.
  size_t release = def(leg + ".sideward.rest_tone_release", 1.0, "1", "Knops 2013, eq. (2.84) / Section 3.2.2",
                       "fraction of the ThC resting spring constants that needs an active antagonist during "
                       "sideward stepping (1: both k decay to 0 when both PR MNs are silent)", 0, 1);
  for (size_t mus : {m.joints()[L.pr.joint].muscle_inc, m.joints()[L.pr.joint].muscle_dec})
    m.add_modulation({mus, release, {after(t_side), before(t_side_end)}, kNoIndex, Modulation::RestTone});
  m.add_modulation({L.sf, drive, {after(t_side_end)}, zero});
  m.add_modulation({L.fe.cpg_dec, ext, {after(t_side_end)}, s_ext});
  m.add_modulation({L.fe.cpg_inc, flx, {after(t_side_end)}, s_flx});
}

}  // namespace

// One leg's parameters, neurons, synapses and sensory couplings. The order of the steps is the
// order of the leg's states and parameters in every output file and saved config (docs/hdf5.md),
// and each step reads indices declared by the ones before it.
LegNetwork add_leg_network(NetworkModel& m, const NeuronClasses& c, const std::string& leg, const LegOptions& o) {
  Def def{m};
  LegNetwork L;
  L.leg = leg;
  auto mid = [&](JointType t) {
    JointTable tab = joint_table(leg, t, t == JointType::Thc ? o.thc_set : "");
    return 0.5 * (tab.angle_min_deg + tab.angle_max_deg);
  };
  // Order PR, LD, FE as in Fig. 2.13 (top to bottom).
  L.pr = add_joint_network(m, c, leg, JointType::Thc, mid(JointType::Thc), o.thc_set,
                           o.direction_switch ? CpgToIn::Both : CpgToIn::Parallel);
  // LD starts levated (swing): without CS input the levator is active (Section 2.5.3).
  JointTable ctr = joint_table(leg, JointType::Ctr);
  L.ld = add_joint_network(m, c, leg, JointType::Ctr, ctr.angle_max_deg);
  L.fe = add_joint_network(m, c, leg, JointType::Fti, mid(JointType::Fti), "",
                           o.crossed_fe ? CpgToIn::Crossed : CpgToIn::Parallel);
  L.beta_state = m.joints()[L.ld.joint].angle_state;
  L.gamma_state = m.joints()[L.fe.joint].angle_state;
  add_sensory_coupling(m, c, def, L, o);
  if (o.ld_release_ms >= 0) add_levator_hold(m, c, def, L, o);
  if (o.direction_switch) add_direction_switch(m, c, def, L);
  return L;
}

std::unique_ptr<NetworkModel> build_leg_model(const std::string& leg, LegOptions o) {
  auto m = std::make_unique<NetworkModel>("leg");
  NeuronClasses c = define_neuron_classes(*m, o.motoneuron);
  if (leg == "hind") o.crossed_fe = true;
  add_leg_network(*m, c, leg, o);
  return m;
}

void set_coupling_gate(ThreeLegOptions& o, const std::string& g) {
  if (g == "target_swing") o.gate = ThreeLegOptions::CouplingGate::TargetSwing;
  else if (g == "source_contact") o.gate = ThreeLegOptions::CouplingGate::SourceContact;
  else throw Error("unknown coupling_gate '" + g + "' (expected target_swing or source_contact)");
}

void set_coupling_variant(ThreeLegOptions& o, const std::string& v) {
  using S = CouplingSign;
  if (v == "inhibitory") o.sign[0] = o.sign[1] = o.sign[2] = S::Inhibitory;
  else if (v == "excitatory") o.sign[0] = o.sign[1] = o.sign[2] = S::Excitatory;
  else if (v == "mixed") {  // Fig. 3.20 E / 3.22 E: excitatory from front and hind, inhibitory from middle
    o.sign[0] = S::Excitatory;
    o.sign[1] = S::Inhibitory;
    o.sign[2] = S::Excitatory;
  } else
    throw Error("unknown coupling variant '" + v + "' (expected inhibitory, excitatory or mixed)");
}

std::unique_ptr<NetworkModel> build_three_leg_model(const ThreeLegOptions& o) {
  auto m = std::make_unique<NetworkModel>("three_legs");
  NeuronClasses c = define_neuron_classes(*m, o.motoneuron);
  Def def{*m};
  const char* k33 = "Knops 2013, Section 3.3";
  const bool tripod = o.gait == "tripod";
  if (!tripod && o.gait != "tetrapod") throw Error("unknown gait '" + o.gait + "' (expected tetrapod or tripod)");
  const double T = tripod ? 442.0 : 510.0, start = 1500.0;
  // Start times (Section 2.5.4): each leg is held in stance by central inhibition of its
  // levator CPG (CS input on at 100 ms for all legs) and released at its start time: tetrapod
  // hind first, middle +T/3, front +2T/3 (Fig. 3.21); tripod middle first, front and hind
  // +T/2 together (Fig. 3.23). Releasing from a held state makes the first lift-off follow the
  // release at the same delay in every leg, so the lags are those of the start times.
  std::vector<std::string> legs = {"front", "middle", "hind"};
  double release[3];
  if (tripod) {
    release[1] = start;
    release[0] = release[2] = start + T / 2;
  } else {
    release[2] = start;
    release[1] = start + T / 3;
    release[0] = start + 2 * T / 3;
  }
  const size_t period = def("gait.period_ms", T, "ms", std::string(k33) + " (T_4pod = 510 ms, T_3pod = 442 ms)",
      "cycle period of the gait: spacing of the start times and of the contralateral copy", 1);
  const size_t lag = def("contralateral.lag", tripod ? 0.5 : 1.0 / 3, "1", "Knops 2013, Sections 2.5.4 and 3.3 (33% tetrapod, 50% tripod)",
      "phase lag of the right side (R1-R3) behind the left (L1-L3) in the six-leg output", 0, 1);
  m->set_contralateral_copy({lag, period});
  std::vector<LegNetwork> L;
  for (int i = 0; i < 3; ++i) {
    LegOptions lo;
    lo.direction_switch = o.direction_switch;
    lo.crossed_fe = legs[i] == "hind";
    lo.g_pr_swing = 1.6;
    lo.g_pr_stance = 3.3;
    lo.g_pr_source = "Knops 2013, Section 3.3 (IN16: 1.6 -> 3.3 nS)";
    lo.cs_on_ms = 100.0;
    lo.cs_on_source = std::string(kChoice) + ": CS input on for all legs; the start times are ld_release_ms";
    lo.ld_release_ms = release[i];
    lo.ld_release_source = std::string("Knops 2013, Section 2.5.4 (start times staggered by ") +
                           (tripod ? "1/2" : "1/3") + " of the period; first release at 1500 ms, a choice)";
    L.push_back(add_leg_network(*m, c, legs[i], lo));
    if (tripod) {
      // Section 3.3 changes g_app3 0.23 -> 0.26, g_app4 0.1843 -> 0.17 for a 1:1 LD relation
      // and 442 ms. In phasmid's LD (docs/walking_model.md) 0.31 / 0.17 nS give 224 : 222 ms
      // (446 ms) in isolation.
      m->parameters().set(legs[i] + ".ctr.cpg_lev.g_app", 0.31, "tripod");
      m->parameters().set(legs[i] + ".ctr.cpg_dep.g_app", 0.17, "tripod");
    }
  }
  // Gait transitions (Section 3.3, Figs. 3.24-3.27): at gait.switch_ms the LD drives of all
  // legs change to the other gait's values; together with each leg's levator hold
  // (<leg>.command.ld_hold_ms) and reset (<leg>.command.ld_release2_ms) this re-phases the legs.
  size_t t_switch = def("gait.switch_ms", kNever, "ms", "Knops 2013, Section 3.3 (gait transitions)",
                        "central command: LD drives change to the other gait's values", 0);
  size_t g_lev2 = def("gait.switch.g_app_lev", tripod ? 0.34 : 0.31, "nS",
                      "the other gait's levator drive (docs/walking_model.md)", "levator CPG drive after gait.switch_ms", 0);
  size_t g_dep2 = def("gait.switch.g_app_dep", tripod ? 0.14 : 0.17, "nS",
                      "the other gait's depressor drive (docs/walking_model.md)", "depressor CPG drive after gait.switch_ms", 0);
  for (int i = 0; i < 3; ++i) {
    m->add_modulation({L[i].ld.cpg_inc, g_lev2, {after(t_switch)}, m->parameters().index(legs[i] + ".ctr.cpg_lev.g_app")});
    m->add_modulation({L[i].ld.cpg_dec, g_dep2, {after(t_switch)}, m->parameters().index(legs[i] + ".ctr.cpg_dep.g_app")});
  }
  // Intersegmental couplings (Section 2.5.4, Fig. 2.15): beta of each leg to the next caudal
  // PR sensory IN, front -> middle -> hind -> front. While the source leg has ground contact
  // and the target leg is lifted, the target's IN16 drive changes by g (weak inhibitory:
  // -0.6 nS, 1.6 -> 1.0 nS; with own ground contact it stays 3.3 nS, Section 3.3).
  const double g_abs = o.strong ? 1.5 : 0.6;
  for (int i = 0; i < 3; ++i) {
    int j = (i + 1) % 3;
    double sign = o.sign[i] == CouplingSign::Inhibitory ? -1.0 : 1.0;
    size_t g = def("coupling." + legs[i] + "_to_" + legs[j] + ".g", sign * g_abs, "nS",
                   o.strong ? std::string(kChoice) + ": 'strong' coupling (2.5x the weak 0.6 nS of Section 3.3)"
                            : std::string(k33) + " (Delta g_app,IN16 = 0.6 nS; negative: inhibitory)",
                   o.gate == ThreeLegOptions::CouplingGate::TargetSwing
                       ? "change of the target leg's PR sensory IN drive while the source leg has ground contact and "
                         "the target leg is lifted (negative: inhibitory)"
                       : "change of the target leg's PR sensory IN drive while the source leg has ground contact "
                         "(coupling_gate = source_contact; negative: inhibitory)");
    std::vector<Condition> when{below(L[i].beta_state, L[i].beta_thr_pr, L[i].width)};
    if (o.gate == ThreeLegOptions::CouplingGate::TargetSwing)
      when.push_back(above(L[j].beta_state, L[j].beta_thr_pr, L[j].width));
    m->add_modulation({L[j].pr.sens_exc, g, when});
  }
  return m;
}

std::unique_ptr<NetworkModel> build_curve_walking_model(MotoneuronModel mn) {
  // Section 3.2.3: two middle legs (L2, R2; Table A.17 ThC as in Knops et al. 2012) with the
  // direction switch, alternating with half a period; the other legs are passive supports.
  auto m = std::make_unique<NetworkModel>("curve_walking");
  NeuronClasses c = define_neuron_classes(*m, mn);
  Def def{*m};
  for (const char* leg : {"L2", "R2"}) {
    LegOptions o;
    o.thc_set = "A.17";
    o.direction_switch = true;
    o.cs_on_ms = 100.0;
    o.cs_on_source = std::string(kChoice) + ": CS input on; the start time is ld_release_ms";
    o.ld_release_ms = std::string(leg) == "L2" ? 1500.0 : 1755.0;
    o.ld_release_source = "Knops 2013, Section 3.2.3 (left and right middle legs alternate with half a period, 255 ms)";
    o.ld_hold_g_pr = 5.0;
    o.ld_hold_g_pr_source = std::string(kChoice) + ": PR silent until the start time, as syn.command_inh.g (Section 2.5.3: the PR is a reflex chain)";
    add_leg_network(*m, c, leg, o);
  }
  const size_t reach = def("body.reach_mm", 15.0, "mm", std::string(kChoice) + ": horizontal distance ThC joint - foot (femur 13 mm, tibia 12 mm, Table A.13, projected)",
      "length of the leg's horizontal lever in the kinematic body model", 0);
  const size_t half_width = def("body.half_width_mm", 2.0, "mm", std::string(kChoice) + ": half the mesothorax width",
                                "lateral offset of the ThC joints", 0);
  m->set_body_geometry({"L2", "R2", reach, half_width});
  return m;
}

}  // namespace phasmid::model
