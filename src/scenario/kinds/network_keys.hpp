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

// The settings the method study chose for the network kinds (bench/results "Method
// study": the cheapest within 0.01 ms and 0.01 deg of CVODES BDF at 1e-10). With spiking
// motoneurons Dormand-Prince 5(4) per joint at rtol = atol = 1e-6 (joint, leg, three legs;
// BDF needs 1e-8 or misses at 1e-7, at 1.4-1.8x the time), in phasmid's own stepper (dopri5:
// ARKODE's steps at less work per step, bench/results "Dormand-Prince of our own"). With
// rate motoneurons, whose interneuron potentials are too stiff for an explicit method (3.5-7x
// slower), CVODES BDF at `rate_rtol`.
inline RunSettings network_defaults(model::MotoneuronModel mn, double rate_rtol) {
  RunSettings s;
  if (mn == model::MotoneuronModel::Spiking) {
    s.solver.integrator = solver::IntegratorKind::Dopri5;
    s.solver.rtol = s.solver.atol = 1e-6;
    s.solver.partitioning = solver::Partitioning::On;
  } else {
    s.solver.rtol = s.solver.atol = rate_rtol;
  }
  return s;
}

}  // namespace phasmid::scenario::kinds
