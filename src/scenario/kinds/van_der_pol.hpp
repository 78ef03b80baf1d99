#pragma once
// The van der Pol oscillator x'' - mu (1 - x^2) x' + x = 0 with time in ms (van der Pol 1926),
// x presented as a joint angle (rad) with its velocity so that the generic features (period,
// extremal angles) apply. Names carry a prefix: the built-in kind "van_der_pol" uses "vdp"
// (vdp.mu, vdp.fti.gamma); tests register the same model under other names.
#include <string>

#include "model/ode_model.hpp"

namespace phasmid::scenario::kinds {

class VanDerPolModel : public model::OdeModelT<VanDerPolModel> {
 public:
  VanDerPolModel(const std::string& prefix, std::string kind) : kind_(std::move(kind)) {
    const size_t x = add_state(prefix + ".fti.gamma", "rad");
    const size_t v = add_state(prefix + ".fti.gamma_dot", "rad/ms");
    angles_.push_back({prefix, "fti", x, v});
    mu_ = params_.add({prefix + ".mu", 1.0, "1", "van der Pol (1926)", "damping strength", 0.0, 100.0});
    x0_ = params_.add({prefix + ".x0", 2.0, "rad", "test choice", "initial x (v = 0)", -10.0, 10.0});
  }
  std::string kind() const override { return kind_; }
  std::vector<double> initial_state(const std::vector<double>& p) const override { return {p[x0_], 0.0}; }
  template <class T>
  void eval(double, const T* y, const T* p, T* ydot) const {
    ydot[0] = y[1];
    ydot[1] = p[mu_] * (T(1.0) - y[0] * y[0]) * y[1] - y[0];
  }

 private:
  std::string kind_;
  size_t mu_, x0_;
};

}  // namespace phasmid::scenario::kinds
