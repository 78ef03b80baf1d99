#pragma once
// [model] keys shared by the joint and network kinds: which leg and joint, which ThC table,
// which motoneuron formulation (docs/config.md). Errors name file:line.
#include <string>

#include "common/error.hpp"
#include "model/leg_tables.hpp"
#include "model/network_model.hpp"
#include "scenario/registry.hpp"
#include "scenario/scenario.hpp"

namespace phasmid::scenario::kinds {

struct JointKeys {
  std::string leg = "middle";
  model::JointType joint = model::JointType::Fti;
  std::string thc_table;
};

// leg (default middle), joint (default fti), thc_table ("", "A.16" or "A.17"), validated
// together against the joint tables.
inline JointKeys joint_keys(const ModelSection& s) {
  JointKeys k;
  k.leg = s.text("leg", "middle");
  if (s.has("thc_table")) k.thc_table = s.choice("thc_table", "", {"A.16", "A.17"});
  try {
    k.joint = model::parse_joint(s.text("joint", "fti"));
    (void)model::joint_table(k.leg, k.joint, k.thc_table);  // validates the leg
  } catch (const Error& e) {
    throw Error(s.where(s.has("joint") ? "joint" : "leg") + ": " + e.what());
  }
  return k;
}

// motoneuron = "spiking" (default) | "rate".
inline model::MotoneuronModel motoneuron_key(const ModelSection& s) {
  if (!s.has("motoneuron")) return model::MotoneuronModel::Spiking;
  try {
    return model::parse_motoneuron_model(s.text("motoneuron", "spiking"));
  } catch (const Error& e) {
    throw Error(s.where("motoneuron") + ": " + e.what());
  }
}

}  // namespace phasmid::scenario::kinds
