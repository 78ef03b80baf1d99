// Model kind "single_joint": one joint's neuronal network with its mechanics (Fig. 2.12,
// model/network_builder.hpp).
#include "model/network_builder.hpp"
#include "scenario/kinds/network_keys.hpp"
#include "scenario/ode_scenario.hpp"

namespace phasmid::scenario {

ModelKind single_joint_kind() {
  return {"single_joint", "one joint's CPG-interneuron-motoneuron network with its mechanics (Fig. 2.12)",
          {"leg", "joint", "thc_table", "motoneuron"}, [](const ModelSection& s) -> std::unique_ptr<Scenario> {
            kinds::JointKeys k = kinds::joint_keys(s);
            const model::MotoneuronModel mn = kinds::motoneuron_key(s);
            return std::make_unique<OdeScenario>(model::build_single_joint_model(k.leg, k.joint, k.thc_table, mn),
                                                 kinds::network_integration(mn, 1e-6, 3e-6));
          }};
}

}  // namespace phasmid::scenario
