#pragma once
// A model kind that lives only in the test tree, registered the way a user's kind would be
// (scenario/registry.hpp): the van der Pol oscillator x'' - mu (1 - x^2) x' + x = 0 with time
// in ms, its x presented as a joint angle (rad) so that the generic features (period, extremal
// angles) apply. Its known periods (van der Pol 1926; e.g. Strogatz, Nonlinear Dynamics and
// Chaos, 2nd ed., Sect. 7.5; T(1) = 6.6633, T(2) = 7.6299, T(5) = 11.6125) check the whole
// chain config -> kind -> scenario -> verb.
#include <memory>

#include "model/ode_model.hpp"
#include "scenario/ode_scenario.hpp"
#include "scenario/registry.hpp"

namespace phasmid::test {

class VanDerPolModel : public model::OdeModelT<VanDerPolModel> {
 public:
  VanDerPolModel() {
    const size_t x = add_state("toy.fti.gamma", "rad");
    const size_t v = add_state("toy.fti.gamma_dot", "rad/ms");
    angles_.push_back({"toy", "fti", x, v});
    mu_ = params_.add({"toy.mu", 1.0, "1", "van der Pol (1926)", "damping strength", 0.0, 100.0});
    x0_ = params_.add({"toy.x0", 2.0, "rad", "test choice", "initial x (v = 0)", -10.0, 10.0});
  }
  std::string kind() const override { return "toy_vdp"; }
  std::vector<double> initial_state(const std::vector<double>& p) const override { return {p[x0_], 0.0}; }
  template <class T>
  void eval(double, const T* y, const T* p, T* ydot) const {
    ydot[0] = y[1];
    ydot[1] = p[mu_] * (T(1.0) - y[0] * y[0]) * y[1] - y[0];
  }

 private:
  size_t mu_, x0_;
};

// The kind's one registration line (a built-in kind's would be in builtin_kinds.def).
inline const scenario::RegisterModelKind kToyKind{
    {"toy_vdp", "van der Pol oscillator (test kind)", {}, [](const scenario::ModelSection&) {
       return std::unique_ptr<scenario::Scenario>(
           std::make_unique<scenario::OdeScenario>(std::make_unique<VanDerPolModel>()));
     }}};

}  // namespace phasmid::test
