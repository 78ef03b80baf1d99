#pragma once
// Pieces shared by the feature source files (not part of the API; see features.hpp):
// values with gradients (Dual), the contact legs' root levels, and the per-leg gait features.
//   features.cpp          per-channel features, the derived 0/1 features, the entry points
//   leg_features.cpp      per-leg gait features, phase lags between legs, gait class
//   feature_roots.cpp     the root functions a run must locate for them
//   feature_catalogue.cpp what each model can produce (kept in step by test_feature_catalogue)
//   features_h5.cpp       /features in HDF5 files
#include <map>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "features/features.hpp"

namespace phasmid::features::detail {

// A value with its gradient with respect to the sensitivity parameters (empty gradient: none).
struct Dual {
  double v = 0.0;
  Eigen::VectorXd g;
};
inline Dual operator+(const Dual& a, const Dual& b) { return {a.v + b.v, a.g + b.g}; }
inline Dual operator-(const Dual& a, const Dual& b) { return {a.v - b.v, a.g - b.g}; }
inline Dual operator/(const Dual& a, const Dual& b) {
  return {a.v / b.v, (a.g * b.v - a.v * b.g) / (b.v * b.v)};
}
inline Dual scaled(const Dual& a, double c) { return {a.v * c, a.g * c}; }

inline Dual mean(const std::vector<Dual>& xs, size_t ns) {
  Dual m{0.0, Eigen::VectorXd::Zero(ns)};
  for (auto& x : xs) m = m + x;
  return scaled(m, 1.0 / xs.size());
}

struct DualFeature {
  std::string name;
  Dual value;
  std::string unit;
};

// ---- contact legs (docs/walking_model.md) ---------------------------------------------------
// Stance (ground contact) is beta below the threshold of a contact leg the model declares
// (model::ContactLeg; 38 deg, Section 3.2, the criterion that switches the PR sensory pathway).
// Touch-down is beta falling through it, lift-off beta rising through it; both are located by
// root finding. The PR system's retractor CPG neuron (Figs. 3.20-3.22 plot it against beta)
// counts as active above the declared level; below it the PR system is in protraction.
constexpr size_t kNoState = static_cast<size_t>(-1);
struct LegRoot {
  std::string leg;
  size_t beta_state;
  double threshold_deg;
  size_t retractor_state = kNoState;  // if the leg has a PR network
  double retractor_level_mV = 0.0;
};

// The contact legs in declaration order, levels from the parameter vector p (empty: the model's
// own values).
std::vector<LegRoot> leg_roots(const model::OdeModel& model, const std::vector<double>& p = {});

// Ipsilateral leg pairs (a, b) of the phase lags phase_lag.<a>_to_<b>; gait_class reads the
// first, second and fourth.
constexpr const char* kLagPairs[][2] = {{"hind", "middle"}, {"middle", "front"}, {"front", "hind"}, {"hind", "front"}};

bool has_three_contact_legs(const model::OdeModel& model);

// The touch-down and lift-off times (ms, with dt/dp when with_grad) of the contact leg `leg`
// after opt.discard_ms, debounced as the per-leg features count them. `roots`: feature_roots.
struct ContactTimes {
  std::vector<Dual> touchdown, liftoff;
};
ContactTimes contact_times(const model::OdeModel& model, const solver::SolveResult& res, const FeatureOptions& opt,
                           bool with_grad, const std::vector<solver::RootSpec>& roots, const std::string& leg);

// The per-leg features and the phase lags between legs of a run (docs/walking_model.md), in
// catalogue order. `roots`: feature_roots(model), whose state indices the event-time formula reads.
std::vector<DualFeature> leg_features(const model::OdeModel& model, const solver::SolveResult& res,
                                      const FeatureOptions& opt, bool with_grad,
                                      const std::vector<solver::RootSpec>& roots);

}  // namespace phasmid::features::detail
