#pragma once
// Gait features from located events (docs/features.md): extrema of every joint angle are found
// by CVODES root finding on the angular velocity, so feature values are exact up to the
// solver tolerance and differentiable with respect to the parameters (see
// src/sensitivity/event_time.hpp).
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "model/ode_model.hpp"
#include "solver/simulator.hpp"

namespace phasmid::io {
class H5Writer;
class H5Reader;
}  // namespace phasmid::io

namespace phasmid::features {

struct FeatureOptions {
  double discard_ms = 0;       // events before this time (transient) are ignored
  // A turning point of the gait cycle must be followed by a swing of more than
  // max(min_swing_deg, min_swing_fraction * angle range) the other way (see docs/features.md).
  double min_swing_deg = 0.5;
  double min_swing_fraction = 0.3;
  // Walking models: swing or stance episodes shorter than this are ripples of beta around
  // the ground-contact threshold and are ignored (docs/walking_model.md).
  double min_contact_ms = 40.0;
  size_t root_offset = 0;      // index of the first feature root in the RootSpec list given to run()
};

struct Feature {
  std::string name;  // "period_ms", "middle.fti.flexion_ms", ...
  double value;
  std::string unit;  // "ms", "deg", "1"
};

// Per-parameter derivative of a feature (with respect to result.sens_params, in order).
struct FeatureGradient {
  Feature feature;
  Eigen::VectorXd gradient;  // d value / d p_j, in unit per parameter unit
};

// Gait class from the ipsilateral phase lags (each in [0, 1)): 2 tripod (front and hind in
// phase, middle antiphase), 1 tetrapod (hind -> middle -> front lags 1/3), 0 irregular;
// a lag counts when within `tolerance` (circular distance, fraction of the period).
int classify_gait(double hind_to_middle, double middle_to_front, double hind_to_front, double tolerance = 0.1);
const char* gait_class_name(int gait_class);

// One root per angle channel, in channel order: g = y[velocity_state] - 0, both directions;
// then, for walking models, one per leg: beta crossing `<leg>.coupling.beta_thr_pr`
// (touch-down falling, lift-off rising), used by the per-leg gait features; then one per leg
// with a PR network: its retractor CPG `<leg>.thc.cpg_ret.V` crossing `syn.cpg_in.V_h`.
// Pass these first in the root list given to Simulator::run (or set FeatureOptions::root_offset).
// The crossing levels come from the parameter vector p (the model's own values without it):
// pass the vector the run uses, so that a run with a perturbed or fitted threshold locates its
// crossings at that threshold.
std::vector<solver::RootSpec> feature_roots(const model::OdeModel& model, const std::vector<double>& p);
std::vector<solver::RootSpec> feature_roots(const model::OdeModel& model);

// Features of every angle channel `<leg>.<joint>` (see docs/features.md):
//   period_ms, <phase_inc>_ms, <phase_dec>_ms, <phase_inc>_fraction, phase_ratio,
//   angle_min_deg, angle_max_deg; plus a global `period_ms` (the first channel's period).
// Walking models add per leg `<leg>.step_period_ms`, `<leg>.stance_ms`, `<leg>.swing_ms`,
// `<leg>.duty_factor`, `<leg>.protraction_in_stance_fraction`, `<leg>.stance_retraction_fraction`,
// and across legs `phase_lag.<a>_to_<b>` and `gait_class` (docs/walking_model.md); all with
// event-time gradients, gait_class with a zero one.
// Features that cannot be computed (too few cycles after discard_ms) are omitted.
std::vector<Feature> compute_features(const model::OdeModel& model, const solver::SolveResult& result,
                                      const FeatureOptions& options = {});

// The same features with their derivatives with respect to result.sens_params, from the
// event-time sensitivities (implicit-function formula). Needs a run with sensitivities.
std::vector<FeatureGradient> compute_feature_gradients(const model::OdeModel& model,
                                                       const solver::SolveResult& result,
                                                       const FeatureOptions& options = {});

// `/features/<name>` scalar datasets with a `units` attribute (docs/hdf5.md).
void write_features_h5(io::H5Writer& out, const std::vector<Feature>& features);
// Reads every scalar under `/features`; throws Error (one line) if the file has no such group.
std::vector<Feature> read_features_h5(const io::H5Reader& in);

}  // namespace phasmid::features
