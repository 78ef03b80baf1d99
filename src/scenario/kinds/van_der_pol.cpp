// Model kind "van_der_pol": x'' - mu (1 - x^2) x' + x = 0 with time in ms (van der Pol 1926),
// x presented as a joint angle (rad) with its velocity so that the generic features (period,
// extremal angles) apply. A test kind for continuation in mu (docs/continuation.md); its
// periods are tabulated in the literature (tests/continuation/test_continuation.cpp).
#include "model/ode_model.hpp"
#include "scenario/ode_scenario.hpp"
#include "scenario/registry.hpp"

namespace phasmid::scenario {
namespace {

class VanDerPolModel : public model::OdeModelT<VanDerPolModel> {
 public:
  VanDerPolModel() {
    const size_t x = add_state("vdp.fti.gamma", "rad");
    const size_t v = add_state("vdp.fti.gamma_dot", "rad/ms");
    angles_.push_back({"vdp", "fti", x, v});
    mu_ = params_.add({"vdp.mu", 1.0, "1", "van der Pol (1926)", "damping strength", 0.0, 100.0});
    x0_ = params_.add({"vdp.x0", 2.0, "rad", "test choice", "initial x (v = 0)", -10.0, 10.0});
  }
  std::string kind() const override { return "van_der_pol"; }
  std::vector<double> initial_state(const std::vector<double>& p) const override { return {p[x0_], 0.0}; }
  template <class T>
  void eval(double, const T* y, const T* p, T* ydot) const {
    ydot[0] = y[1];
    ydot[1] = p[mu_] * (T(1.0) - y[0] * y[0]) * y[1] - y[0];
  }

 private:
  size_t mu_, x0_;
};

}  // namespace

ModelKind van_der_pol_kind() {
  return {"van_der_pol", "van der Pol oscillator x'' - mu (1 - x^2) x' + x = 0, time in ms (test kind)", {},
          [](const ModelSection&) -> std::unique_ptr<Scenario> {
            return std::make_unique<OdeScenario>(std::make_unique<VanDerPolModel>());
          }};
}

}  // namespace phasmid::scenario
