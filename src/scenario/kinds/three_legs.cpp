// Model kind "three_legs": front, middle and hind leg with intersegmental coupling, in the
// tetrapod or tripod gait (model/leg_network.hpp, docs/walking_model.md).
#include "model/leg_network.hpp"
#include "scenario/kinds/network_keys.hpp"
#include "scenario/ode_scenario.hpp"

namespace phasmid::scenario {

ModelKind three_legs_kind() {
  return {"three_legs", "three ipsilateral legs with intersegmental coupling, tetrapod or tripod (Section 2.6)",
          {"gait", "coupling", "coupling_strength", "coupling_gate", "direction_switch", "motoneuron"},
          [](const ModelSection& s) -> std::unique_ptr<Scenario> {
            model::ThreeLegOptions o;
            o.direction_switch = s.boolean("direction_switch", false);
            o.motoneuron = kinds::motoneuron_key(s);
            o.gait = s.text("gait", "tetrapod");
            o.strong = s.choice("coupling_strength", "weak", {"weak", "strong"}) == "strong";
            try {
              model::set_coupling_variant(o, s.text("coupling", "inhibitory"));
            } catch (const Error& e) {
              throw Error(s.where("coupling") + ": " + e.what());
            }
            try {
              model::set_coupling_gate(o, s.text("coupling_gate", "target_swing"));
            } catch (const Error& e) {
              throw Error(s.where("coupling_gate") + ": " + e.what());
            }
            try {
              // Rate motoneurons: BDF per joint needs 1e-7 (1e-6 misses the duration gate).
              return std::make_unique<OdeScenario>(model::build_three_leg_model(o),
                                                   kinds::network_integration(o.motoneuron, 1e-7, 2e-7));
            } catch (const Error& e) {
              throw Error(s.where("gait") + ": " + e.what());
            }
          }};
}

}  // namespace phasmid::scenario
