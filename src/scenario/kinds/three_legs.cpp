// Model kind "three_legs": front, middle and hind leg with intersegmental coupling, in the
// tetrapod or tripod gait (model/leg_network.hpp, docs/walking_model.md).
#include "model/leg_network.hpp"
#include "scenario/kinds/network_keys.hpp"
#include "scenario/ode_scenario.hpp"

namespace phasmid::scenario {

namespace {
// With rate motoneurons CVODES BDF per joint at 1e-7, the method study's cheapest setting
// within 0.01 ms and 0.01 deg of BDF at 1e-10 (1e-6 misses by 0.02 ms; explicit methods,
// bounded by the interneurons' stiffness, take 3.5x the time; docs/benchmarks.md).
RunSettings three_legs_defaults(model::MotoneuronModel mn) {
  if (mn == model::MotoneuronModel::Spiking) return kinds::spiking_network_defaults();
  RunSettings s;
  s.solver.rtol = s.solver.atol = 1e-7;
  return s;
}
}  // namespace

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
              return std::make_unique<OdeScenario>(model::build_three_leg_model(o), three_legs_defaults(o.motoneuron));
            } catch (const Error& e) {
              throw Error(s.where("gait") + ": " + e.what());
            }
          }};
}

}  // namespace phasmid::scenario
