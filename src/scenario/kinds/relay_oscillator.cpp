// Model kind "relay_oscillator": a hybrid oscillator whose right-hand side switches at events,
//   tau dx/dt = u - x,   dz/dt = -k z + c u,   u = +1 until x rises through +a, then -1 until
//   x falls through -a, and so on (a relay with hysteresis).
// The switches are command times resolved by model triggers (model/command_trigger.hpp), so
// the solver applies the saltation terms of docs/sensitivity.md at each one; the kind exists to
// test them (docs/continuation.md). Closed form: from x = -a under u = +1,
// x(t) = 1 - (1 + a) exp(-t/tau) reaches +a after tau ln((1+a)/(1-a)); by symmetry the period
// is T = 2 tau ln((1+a)/(1-a)). Over half a period the flow contracts x by exp(-T/(2 tau)) =
// (1-a)/(1+a) and the switch at x = +a multiplies it by the saltation factor
// 1 + (f+_x - f-_x)/f-_x = 1 - 2/(1-a) = -(1+a)/(1-a); so the x-multiplier of a cycle is
// (-1)^2 = 1 (the trivial multiplier of an autonomous cycle) and, the monodromy being lower
// triangular, the other multiplier is exp(-k T). Without the saltation terms the x-multiplier
// would be exp(-T/tau). The relay switches kSwitches times, then stays (enough for a transient
// and the cycles of a continuation: each cycle is integrated from its section with no switch
// fired yet, u = +1 there).
#include <algorithm>
#include <string>

#include "model/ode_model.hpp"
#include "scenario/ode_scenario.hpp"
#include "scenario/registry.hpp"

namespace phasmid::scenario {
namespace {

constexpr size_t kSwitches = 200;

class RelayOscillatorModel : public model::OdeModelT<RelayOscillatorModel> {
 public:
  RelayOscillatorModel() {
    add_state("relay.x", "1");
    add_state("relay.z", "1");
    a_ = params_.add({"relay.a", 0.5, "1", "test choice", "relay thresholds -a, +a on x", 1e-3, 0.999});
    tau_ = params_.add({"relay.tau_ms", 10.0, "ms", "test choice", "time constant of x", 1e-3, 1e6});
    k_ = params_.add({"relay.k", 0.05, "1/ms", "test choice", "decay rate of z", 0.0, 100.0});
    c_ = params_.add({"relay.c", 0.05, "1/ms", "test choice", "drive of z by the relay", -100.0, 100.0});
    std::vector<model::CommandTrigger> triggers;
    for (size_t i = 0; i < kSwitches; ++i) {
      const std::string name = "relay.switch_" + std::to_string(i + 1) + "_ms";
      switch_.push_back(params_.add({name, model::kUnresolvedMs, "ms", "resolved by the relay's threshold crossings",
                                     "time of switch " + std::to_string(i + 1)}));
      model::CommandTrigger t;
      const bool up = i % 2 == 0;  // odd switches: x rising through +a; even: x falling through -a
      t.event = up ? "relay.x rises through +a" : "relay.x falls through -a";
      t.targets = {switch_.back()};
      t.state = 0;
      t.level_param = a_;
      t.level_scale = up ? 1.0 : -1.0;
      t.direction = up ? 1 : -1;
      if (i > 0) t.after_param = switch_[i - 1];
      t.debounce_ms = 0.0;
      triggers.push_back(t);
    }
    set_triggers(std::move(triggers));
  }
  std::string kind() const override { return "relay_oscillator"; }
  std::vector<double> initial_state(const std::vector<double>&) const override { return {0.0, 0.0}; }
  template <class T>
  void eval(double t, const T* y, const T* p, T* ydot) const {
    // Switch times resolve in order, so the fired ones are a prefix of switch_.
    size_t fired = 0;
    while (fired < switch_.size() && model::value_of(p[switch_[fired]]) <= t) ++fired;
    const double u = fired % 2 == 0 ? 1.0 : -1.0;
    ydot[0] = (T(u) - y[0]) / p[tau_];
    ydot[1] = -p[k_] * y[1] + p[c_] * u;
  }

 private:
  size_t a_, tau_, k_, c_;
  std::vector<size_t> switch_;
};

}  // namespace

ModelKind relay_oscillator_kind() {
  return {"relay_oscillator", "relay oscillator with hysteresis, switched by event triggers (test kind for saltation terms)",
          {}, [](const ModelSection&) -> std::unique_ptr<Scenario> {
            return std::make_unique<OdeScenario>(std::make_unique<RelayOscillatorModel>());
          }};
}

}  // namespace phasmid::scenario
