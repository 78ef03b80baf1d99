// Model kind "leg": the three joint networks of one leg with their sensory coupling and, with
// direction_switch, the forward/sideward switch (model/leg_network.hpp).
#include "model/leg_network.hpp"
#include "scenario/kinds/network_keys.hpp"
#include "scenario/ode_scenario.hpp"

namespace phasmid::scenario {

ModelKind leg_kind() {
  return {"leg", "one leg: ThC, CTr and FTi networks with sensory coupling (Section 2.5)",
          {"leg", "thc_table", "direction_switch", "motoneuron", "start_ms"},
          [](const ModelSection& s) -> std::unique_ptr<Scenario> {
            kinds::JointKeys k = kinds::joint_keys(s);
            model::LegOptions o;
            o.thc_set = k.thc_table;
            o.direction_switch = s.boolean("direction_switch", false);
            o.motoneuron = kinds::motoneuron_key(s);
            if (s.has("start_ms")) {
              double start = s.number("start_ms", 0);
              if (!(start >= 0)) throw Error(s.where("start_ms") + ": 'start_ms' must be a number >= 0 (ms)");
              o.hold_until(start);
            }
            return std::make_unique<OdeScenario>(model::build_leg_model(k.leg, o),
                                                 kinds::network_integration(o.motoneuron, 1e-8, 2e-7));
          }};
}

}  // namespace phasmid::scenario
