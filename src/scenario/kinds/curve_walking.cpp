// Model kind "curve_walking": the two middle legs walking a curve (model/leg_network.hpp,
// docs/walking_model.md).
#include "model/leg_network.hpp"
#include "scenario/kinds/network_keys.hpp"
#include "scenario/ode_scenario.hpp"

namespace phasmid::scenario {

ModelKind curve_walking_kind() {
  return {"curve_walking", "the left and right middle legs walking a curve (Section 2.5.3)", {"motoneuron"},
          [](const ModelSection& s) -> std::unique_ptr<Scenario> {
            const model::MotoneuronModel mn = kinds::motoneuron_key(s);
            return std::make_unique<OdeScenario>(model::build_curve_walking_model(mn),
                                                 kinds::network_integration(mn, 1e-8, 3e-7));
          }};
}

}  // namespace phasmid::scenario
