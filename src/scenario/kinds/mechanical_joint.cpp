// Model kind "mechanical_joint": one joint driven by its mechanics alone, the spring constants
// switching at the Section 3.1.1 phase times (model/mechanical_joint_model.hpp).
#include "model/mechanical_joint_model.hpp"
#include "scenario/kinds/network_keys.hpp"
#include "scenario/ode_scenario.hpp"

namespace phasmid::scenario {

ModelKind mechanical_joint_kind() {
  return {"mechanical_joint", "one joint driven by its mechanics alone (Section 3.1.1)",
          {"leg", "joint", "thc_table", "start_phase"}, [](const ModelSection& s) -> std::unique_ptr<Scenario> {
            kinds::JointKeys k = kinds::joint_keys(s);
            model::JointNaming n = model::joint_naming(k.joint);
            std::string start = s.choice("start_phase", n.phase_inc, {n.phase_inc, n.phase_dec});
            return std::make_unique<OdeScenario>(
                model::MechanicalJointModel::section311(k.leg, k.joint, start == n.phase_inc, k.thc_table));
          }};
}

}  // namespace phasmid::scenario
