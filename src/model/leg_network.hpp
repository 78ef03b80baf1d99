#pragma once
// Knops (2013) Sections 2.5.3-2.5.4 and 3.2-3.3: the single leg of Fig. 2.13 (PR, LD and FE
// joint networks of Fig. 2.12 coupled by sensory pathways; 24 neurons, 78 equations), the
// direction switch of Fig. 3.11 (SF/SB command neurons with presynaptic inhibition) and the
// three ipsilateral legs of Fig. 2.14 (72 neurons, 234 equations) with the intersegmental
// couplings of Section 3.3 / Fig. 3.19. Every threshold, strength and command time is a named
// parameter (docs/walking_model.md lists names, values, units and sources).
#include <memory>
#include <string>
#include <vector>

#include "model/network_builder.hpp"

namespace phasmid::model {

struct LegOptions {
  std::string thc_set;            // "" (Table A.16 / A.20 / A.23 per leg) or "A.17" (middle leg, Section 3.2.1)
  bool direction_switch = false;  // SF/SB network of Fig. 3.11 gating parallel vs crossed PR connections
  bool crossed_fe = false;        // hind leg: crossed CPG -> IN connections in the FE system (Fig. 3.17)
  // PR sensory IN (IN4 / IN16) drive without and with ground contact, nS, and their sources:
  // 0.60 -> 3.90 for the single leg (Section 3.2), 1.6 -> 3.3 in the three-leg model (Section 3.3).
  double g_pr_swing = 0.60, g_pr_stance = 3.90;
  std::string g_pr_source = "Knops 2013, Section 3.2";
  double cs_on_ms = 200.0;        // end of the initial transient: CS input to LD switched on
  std::string cs_on_source;
  // Central inhibition of the levator CPG (Section 2.5.4): a command neuron holds the leg in
  // stance from t = 0 until ld_release_ms (the leg's start time), and again from ld_hold_ms to
  // ld_release2_ms (gait transitions). Negative ld_release_ms: no hold network.
  double ld_release_ms = -1.0;
  std::string ld_release_source;
  // Inhibition of both PR CPGs by the same command neuron while it holds the leg
  // (<leg>.ld_hold.g_pr, nS): 0 (no synapses) keeps the PR free-running during the hold
  // (three-leg model); curve walking silences it so that every leg starts its PR from the
  // same state whatever its start time.
  double ld_hold_g_pr = 0.0;
  std::string ld_hold_g_pr_source;
  MotoneuronModel motoneuron = MotoneuronModel::Spiking;  // used by build_leg_model

  // A single leg held in stance, both PR CPGs silent, until `start_ms`, as each leg of curve
  // walking (docs/walking_model.md, "Start time of a single leg").
  void hold_until(double start_ms);
};

struct LegNetwork {
  std::string leg;
  JointNetwork pr, ld, fe;
  size_t sf = kNoIndex, sb = kNoIndex;  // command neurons (direction switch)
  size_t beta_state = 0, gamma_state = 0;
  size_t beta_thr_pr = 0, width = 0;    // parameters reused by intersegmental couplings
};

LegNetwork add_leg_network(NetworkModel& m, const NeuronClasses& c, const std::string& leg, const LegOptions& o);

// type "leg": one leg (front, middle, hind); the hind leg gets the crossed FE wiring.
std::unique_ptr<NetworkModel> build_leg_model(const std::string& leg, LegOptions o);

// Intersegmental coupling variants of Fig. 3.19 / Figs. 3.20, 3.22.
enum class CouplingSign { Inhibitory, Excitatory };
struct ThreeLegOptions {
  std::string gait = "tetrapod";  // tetrapod | tripod (LD start times and LD drives)
  // Sign of the connection from front -> middle, middle -> hind, hind -> front (Fig. 3.19 A-C).
  CouplingSign sign[3] = {CouplingSign::Inhibitory, CouplingSign::Inhibitory, CouplingSign::Inhibitory};
  bool strong = false;            // weak (0.6 nS, Section 3.3) or strong strengths
  bool direction_switch = false;
  // When an intersegmental coupling acts (docs/walking_model.md, "Coupling variants"):
  // TargetSwing - while the source leg has ground contact and the target leg is lifted, the
  //   literal reading of Section 3.3's numbers (3.3 nS with both legs in contact, 1.0 nS with the
  //   target lifted); SourceContact - whenever the source leg has ground contact, as a synapse
  //   from the source's beta pathway would ("dampens the excitatory intrasegmental input").
  enum class CouplingGate { TargetSwing, SourceContact } gate = CouplingGate::TargetSwing;
  MotoneuronModel motoneuron = MotoneuronModel::Spiking;
};
std::unique_ptr<NetworkModel> build_three_leg_model(const ThreeLegOptions& o);

// type "curve_walking" (Section 3.2.3): left and right middle legs L2, R2 with direction
// switches, half a period apart, plus the body parameters of body_kinematics.hpp.
std::unique_ptr<NetworkModel> build_curve_walking_model(MotoneuronModel mn = MotoneuronModel::Spiking);
// "inhibitory" | "excitatory" | "mixed" (Fig. 3.19 C: hind -> front excitatory, others inhibitory)
void set_coupling_variant(ThreeLegOptions& o, const std::string& variant);
// "target_swing" | "source_contact" (ThreeLegOptions::gate)
void set_coupling_gate(ThreeLegOptions& o, const std::string& gate);

}  // namespace phasmid::model
