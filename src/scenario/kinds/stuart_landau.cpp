// Model kind "stuart_landau": the Stuart-Landau oscillator in polar normal form,
//   dr/dt = lambda r + c3 r^3 + c5 r^5,   dtheta/dt = omega,
// written in Cartesian coordinates (x, y) = r (cos theta, sin theta). With c3 = -1, c5 = 0
// (the defaults) it is the supercritical Hopf normal form: for lambda > 0 a stable cycle of
// radius sqrt(lambda) and period 2 pi / omega whose nontrivial Floquet multiplier is
// exp(T d/dr(lambda r - r^3)) = exp(-2 lambda T); the cycle shrinks to the equilibrium at the
// Hopf point lambda = 0. With c3 = +1, c5 = -1 the Hopf point is subcritical and the branch
// folds at lambda = -1/4 (r^2 = 1/2) (e.g. Kuznetsov, Elements of Applied Bifurcation Theory,
// 3rd ed., Sect. 3.5). With `transverse = true` in [model] two more states follow a linear
// focus, du/dt = a u - beta v, dv/dt = a v + beta u, uncoupled from the cycle: their multipliers
// are the complex pair exp(a T) exp(+-i beta T), which crosses the unit circle at a = 0 (a torus
// bifurcation of the cycle). With `pair = true` a second, identical oscillator (x2, y2) joins,
// coupled diffusively, dz1/dt += k (z2 - z1), dz2/dt += k (z1 - z2) (z = x + i y): the in-phase
// cycle's antisymmetric perturbations decay with exp(-2 k T) (relative phase) and
// exp(-2 (lambda + k) T) (relative radius), so with k = 0 every relative phase is a cycle of a
// family and the multiplier 1 is double (a neutral direction; docs/continuation.md). A test kind for docs/continuation.md; y is presented as a joint
// angle (its velocity on the cycle is omega x, so x is its velocity channel) for the features.
#include <cmath>

#include "model/ode_model.hpp"
#include "scenario/ode_scenario.hpp"
#include "scenario/registry.hpp"

namespace phasmid::scenario {
namespace {

class StuartLandauModel : public model::OdeModelT<StuartLandauModel> {
 public:
  StuartLandauModel(bool transverse, bool pair) : transverse_(transverse), pair_(pair) {
    const size_t x = add_state("sl.x", "rad");
    const size_t y = add_state("sl.y", "rad");
    if (transverse_) {
      add_state("sl.u", "1");
      add_state("sl.v", "1");
      a_ = params_.add({"sl.a", -0.005, "1/ms", "test choice", "growth rate of the transverse focus", -10.0, 10.0});
      beta_ = params_.add({"sl.beta", 0.013, "rad/ms", "test choice", "rotation rate of the transverse focus", -100.0, 100.0});
    }
    if (pair_) {
      add_state("sl2.x", "rad");
      add_state("sl2.y", "rad");
      k_ = params_.add({"sl.k", 0.0, "1/ms", "test choice", "diffusive coupling of the pair", 0.0, 10.0});
      phase2_ = params_.add({"sl.phase2", 1.0, "rad", "test choice", "initial phase of the second oscillator", -10.0, 10.0});
    }
    angles_.push_back({"sl", "fti", y, x});
    lambda_ = params_.add({"sl.lambda", 0.01, "1/ms", "Hopf normal form", "linear growth rate of r", -10.0, 10.0});
    omega_ = params_.add({"sl.omega", 2.0 * M_PI / 100.0, "rad/ms", "test choice (period 100 ms)",
                          "angular frequency", 1e-6, 100.0});
    c3_ = params_.add({"sl.c3", -1.0, "1/(ms rad^2)", "Hopf normal form", "cubic coefficient of dr/dt", -10.0, 10.0});
    c5_ = params_.add({"sl.c5", 0.0, "1/(ms rad^4)", "Hopf normal form", "quintic coefficient of dr/dt", -10.0, 10.0});
    x0_ = params_.add({"sl.x0", 0.5, "rad", "test choice", "initial x (y = 0)", -10.0, 10.0});
  }
  std::string kind() const override { return "stuart_landau"; }
  std::vector<double> initial_state(const std::vector<double>& p) const override {
    std::vector<double> y0{p[x0_], 0.0};
    if (transverse_) y0.insert(y0.end(), {0.0, 0.0});
    if (pair_) y0.insert(y0.end(), {p[x0_] * std::cos(p[phase2_]), p[x0_] * std::sin(p[phase2_])});
    return y0;
  }
  template <class T>
  void eval(double, const T* y, const T* p, T* ydot) const {
    const T rho = y[0] * y[0] + y[1] * y[1];
    const T g = p[lambda_] + p[c3_] * rho + p[c5_] * rho * rho;
    ydot[0] = g * y[0] - p[omega_] * y[1];
    ydot[1] = g * y[1] + p[omega_] * y[0];
    if (transverse_) {
      ydot[2] = p[a_] * y[2] - p[beta_] * y[3];
      ydot[3] = p[a_] * y[3] + p[beta_] * y[2];
    }
    if (pair_) pair_rhs(y, p, ydot);
  }

 private:
  template <class T>
  void pair_rhs(const T* y, const T* p, T* ydot) const {
    const size_t i = transverse_ ? 4 : 2;
    const T rho = y[i] * y[i] + y[i + 1] * y[i + 1];
    const T g = p[lambda_] + p[c3_] * rho + p[c5_] * rho * rho;
    ydot[i] = g * y[i] - p[omega_] * y[i + 1] + p[k_] * (y[0] - y[i]);
    ydot[i + 1] = g * y[i + 1] + p[omega_] * y[i] + p[k_] * (y[1] - y[i + 1]);
    ydot[0] += p[k_] * (y[i] - y[0]);
    ydot[1] += p[k_] * (y[i + 1] - y[1]);
  }

  bool transverse_, pair_;
  size_t lambda_, omega_, c3_, c5_, x0_, a_ = 0, beta_ = 0, k_ = 0, phase2_ = 0;
};

}  // namespace

ModelKind stuart_landau_kind() {
  return {"stuart_landau", "Stuart-Landau oscillator dr/dt = lambda r + c3 r^3 + c5 r^5, dtheta/dt = omega (test kind)",
          {"transverse", "pair"}, [](const ModelSection& s) -> std::unique_ptr<Scenario> {
            return std::make_unique<OdeScenario>(
                std::make_unique<StuartLandauModel>(s.boolean("transverse", false), s.boolean("pair", false)));
          }};
}

}  // namespace phasmid::scenario
