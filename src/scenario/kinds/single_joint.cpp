// Model kind "single_joint": one joint's neuronal network with its mechanics (Fig. 2.12,
// model/network_builder.hpp).
#include "model/network_builder.hpp"
#include "scenario/kinds/network_keys.hpp"
#include "scenario/ode_scenario.hpp"

namespace phasmid::scenario {

namespace {
// With rate motoneurons the interneurons' potentials are too stiff for an explicit method:
// CVODES BDF, whose 1e-6 meets the method study's accuracy (docs/benchmarks.md).
RunSettings single_joint_defaults(model::MotoneuronModel mn) {
  if (mn == model::MotoneuronModel::Spiking) return kinds::spiking_network_defaults();
  RunSettings s;
  s.solver.rtol = s.solver.atol = 1e-6;
  return s;
}
}  // namespace

ModelKind single_joint_kind() {
  return {"single_joint", "one joint's CPG-interneuron-motoneuron network with its mechanics (Fig. 2.12)",
          {"leg", "joint", "thc_table", "motoneuron"}, [](const ModelSection& s) -> std::unique_ptr<Scenario> {
            kinds::JointKeys k = kinds::joint_keys(s);
            const model::MotoneuronModel mn = kinds::motoneuron_key(s);
            return std::make_unique<OdeScenario>(model::build_single_joint_model(k.leg, k.joint, k.thc_table, mn),
                                                 single_joint_defaults(mn));
          }};
}

}  // namespace phasmid::scenario
