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
// With `flip = true` in [model] two more states (p, q) make a period-doubling (flip) test:
//   u = +1:  dp/dt = -omega q,  dq/dt = omega p,  omega = pi / (tau ln((1+a)/(1-a))),
//   u = -1:  dp/dt = alpha p - kappa p^3,  dq/dt = -beta q.
// Each half period lasts T/2 = tau ln((1+a)/(1-a)), so the u = +1 time of a cycle (split by the
// section or not) rotates (p, q) by exactly pi, the map -I, and the u = -1 half multiplies p by
// exp(alpha T/2) and q by exp(-beta T/2) (linearised at p = q = 0, the cycle). The switches
// depend on x alone, so the monodromy is block lower triangular and its (p, q) block is
// -diag(exp(alpha T/2), exp(-beta T/2)): the multiplier -exp(alpha T/2) passes through -1 at
// alpha = 0. For alpha > 0 the cubic term bounds a cycle of period 2T on which p alternates in
// sign from one T to the next (a supercritical flip).
#include <algorithm>
#include <cmath>
#include <string>

#include "model/ode_model.hpp"
#include "scenario/ode_scenario.hpp"
#include "scenario/registry.hpp"

namespace phasmid::scenario {
namespace {

constexpr size_t kSwitches = 200;

class RelayOscillatorModel : public model::OdeModelT<RelayOscillatorModel> {
 public:
  explicit RelayOscillatorModel(bool flip) : flip_(flip) {
    add_state("relay.x", "1");
    add_state("relay.z", "1");
    if (flip_) {
      add_state("relay.p", "1");
      add_state("relay.q", "1");
      alpha_ = params_.add({"relay.alpha", -0.02, "1/ms", "test choice", "growth rate of p while u = -1 (flip at 0)", -10.0, 10.0});
      beta_ = params_.add({"relay.beta", 0.05, "1/ms", "test choice", "decay rate of q while u = -1", -10.0, 10.0});
      kappa_ = params_.add({"relay.kappa", 0.01, "1/ms", "test choice", "cubic saturation of p while u = -1", 0.0, 10.0});
    }
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
  std::vector<double> initial_state(const std::vector<double>&) const override {
    if (flip_) return {0.0, 0.0, 0.0, 0.0};
    return {0.0, 0.0};
  }
  template <class T>
  void eval(double t, const T* y, const T* p, T* ydot) const {
    // Switch times resolve in order, so the fired ones are a prefix of switch_.
    size_t fired = 0;
    while (fired < switch_.size() && model::value_of(p[switch_[fired]]) <= t) ++fired;
    const double u = fired % 2 == 0 ? 1.0 : -1.0;
    ydot[0] = (T(u) - y[0]) / p[tau_];
    ydot[1] = -p[k_] * y[1] + p[c_] * u;
    if (flip_) flip_rhs(u, y, p, ydot);
  }

 private:
  template <class T>
  void flip_rhs(double u, const T* y, const T* p, T* ydot) const {
    using std::log;
    if (u > 0) {
      const T omega = M_PI / (p[tau_] * log((1.0 + p[a_]) / (1.0 - p[a_])));
      ydot[2] = -omega * y[3];
      ydot[3] = omega * y[2];
    } else {
      ydot[2] = p[alpha_] * y[2] - p[kappa_] * y[2] * y[2] * y[2];
      ydot[3] = -p[beta_] * y[3];
    }
  }

  bool flip_;
  size_t a_, tau_, k_, c_, alpha_ = 0, beta_ = 0, kappa_ = 0;
  std::vector<size_t> switch_;
};

}  // namespace

ModelKind relay_oscillator_kind() {
  return {"relay_oscillator", "relay oscillator with hysteresis, switched by event triggers (test kind for saltation terms)",
          {"flip"}, [](const ModelSection& s) -> std::unique_ptr<Scenario> {
            return std::make_unique<OdeScenario>(std::make_unique<RelayOscillatorModel>(s.boolean("flip", false)));
          }};
}

}  // namespace phasmid::scenario
