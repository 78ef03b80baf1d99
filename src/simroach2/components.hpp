#pragma once
// SimRoach2 components: muscles and joint springs from the supplement's tables, and the set of
// components a config's [simroach2] section gives (config/simroach2_section.hpp reads it).
#include <map>
#include <string>

#include "simroach2/muscle.hpp"
#include "simroach2/neuron.hpp"
#include "simroach2/passive_joint.hpp"
#include "simroach2/synapse.hpp"

namespace phasmid::simroach2 {

// `leg_joint` as in the tables: "LF ThC2", ..., "RH FTi".
MuscleParameters muscle_from_tables(const std::string& leg_joint, const std::string& muscle);
PassiveSpringDamper spring_from_tables(const std::string& leg_joint);

struct Components {
  std::map<std::string, NeuronParameters> neurons;
  std::map<std::string, SynapseParameters> synapses;
  std::map<std::string, MuscleParameters> muscles;
  std::map<std::string, PassiveSpringDamper> joints;
};

}  // namespace phasmid::simroach2
