#pragma once
// Assembles networks of Knops (2013) Section 2.5 into a NetworkModel: the neuron-class
// constants of Tables A.1-A.9, and the single-joint network of Fig. 2.12 (8 neurons,
// 26 equations). Names: "<leg>.<joint>.<neuron>.<parameter>", neuron classes "cpg.*",
// "interneuron.*", "mn.*", synapse classes "syn.<class>.*", muscle activation "muscle.*".
#include <memory>
#include <string>

#include "model/network_model.hpp"

namespace phasmid::model {

// Indices of the class-level parameters shared by all joints (defined once per model).
struct NeuronClasses {
  NapIdx cpg_shared, in_mn, sens_inh, sens_exc, sens_exc_ld;  // g_app/epsilon/C_m filled per neuron
  MotoneuronIdx mn;
  SynapseIdx cpg_cpg, in_cpg_inh, in_cpg_exc, in_mn_syn, cpg_in;
};
// With MotoneuronModel::Rate it also defines the rate formulation's parameters (mn.rate.*,
// muscle.rate.gain) and switches the model's motoneurons to it.
NeuronClasses define_neuron_classes(NetworkModel& m, MotoneuronModel mn = MotoneuronModel::Spiking);

// Neuron indices of one joint network (Fig. 2.12), by function. For each joint the "inc"
// muscle increases the angle (retractor, levator, flexor), the "dec" muscle decreases it;
// the sensory pathway excites the inc CPG (sens_exc, IN4/IN8/IN12) and inhibits the dec
// CPG (sens_inh, IN3/IN7/IN11).
struct JointNetwork {
  std::string prefix;
  size_t cpg_inc, cpg_dec, in_inc, in_dec, sens_exc, sens_inh, mn_inc, mn_dec;
  size_t joint;
  // CPG -> IN synapses: "parallel" (inc CPG excites the IN of the dec MN, Fig. 2.12) and,
  // when present, "crossed" (inc CPG excites the IN of its own MN, Figs. 3.11, 3.17).
  size_t syn_par_inc = kNoIndex, syn_par_dec = kNoIndex;  // from cpg_inc / cpg_dec
  size_t syn_crs_inc = kNoIndex, syn_crs_dec = kNoIndex;
  // Sensory IN -> sensory IN excitation (IN4 -> IN3, INCS -> IN7, IN12 -> IN11; Fig. 2.12).
  size_t syn_sens = kNoIndex;
};

// How the CPG drives the MN-inhibiting interneurons: parallel (Fig. 2.12), crossed (the hind
// leg's FE system, Fig. 3.17), or both (the PR system with the direction switch, Fig. 3.11;
// the caller gates them presynaptically).
enum class CpgToIn { Parallel, Crossed, Both };

JointNetwork add_joint_network(NetworkModel& m, const NeuronClasses& c, const std::string& leg, JointType type,
                               double angle0_deg, const std::string& thc_set = "",
                               CpgToIn wiring = CpgToIn::Parallel);

std::unique_ptr<NetworkModel> build_single_joint_model(const std::string& leg, JointType type,
                                                       const std::string& thc_set = "",
                                                       MotoneuronModel mn = MotoneuronModel::Spiking);

}  // namespace phasmid::model
