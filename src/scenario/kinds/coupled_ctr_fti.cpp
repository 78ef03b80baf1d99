// Model kind "coupled_ctr_fti": the CTr and FTi joints of one leg coupled mechanically
// (model/coupled_ctr_fti_model.hpp).
#include "model/coupled_ctr_fti_model.hpp"
#include "scenario/kinds/network_keys.hpp"
#include "scenario/ode_scenario.hpp"

namespace phasmid::scenario {

ModelKind coupled_ctr_fti_kind() {
  return {"coupled_ctr_fti", "the CTr and FTi joints of one leg, mechanically coupled (Section 3.1)",
          {"leg"}, [](const ModelSection& s) -> std::unique_ptr<Scenario> {
            kinds::JointKeys k = kinds::joint_keys(s);
            return std::make_unique<OdeScenario>(std::make_unique<model::CoupledCtrFtiModel>(k.leg));
          }};
}

}  // namespace phasmid::scenario
