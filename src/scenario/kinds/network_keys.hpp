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

// The settings the method study chose for a network with spiking motoneurons (docs/benchmarks.md
// "Method study"): Dormand-Prince 5(4) at rtol = atol = 1e-6, one integrator per joint, meets
// every duration within 0.01 ms and every angle within 0.01 deg of CVODES BDF at 1e-10 on the
// joint, the leg and the three legs, where BDF needs 1e-8 (joint, leg) or misses at 1e-7
// (three legs) and takes 1.4-1.8x the time.
inline RunSettings spiking_network_defaults() {
  RunSettings s;
  s.solver.integrator = solver::IntegratorKind::ErkDp5;
  s.solver.rtol = s.solver.atol = 1e-6;
  s.solver.partitioning = solver::Partitioning::On;
  return s;
}

}  // namespace phasmid::scenario::kinds
