#pragma once
// What a fit compares the model with (each becomes a block of weighted residuals):
//  - FeatureTarget: a gait feature (period, phase durations and ratios, extremal angles)
//    r = (feature - value) / tolerance; gradients from located events.
//  - SwitchCondition: conditions (2.42) of Section 2.3.5: at the switch time T_sw the angle
//    equals the extremal angle with zero velocity (and zero acceleration, i.e. the springs
//    balance there); r = (angle - angle_deg)/tol, velocity/tol, acceleration/tol.
//  - StepCycleTarget: a recording's step cycles (docs/recordings.md), compared with the model's
//    step cycle of one leg: per observable and phase bin r = (sign scale model + offset - data) /
//    sigma (with an estimated sigma, one more residual sqrt(n (2 ln sigma + c)) for its n bins),
//    and the period and duty factor over their sigmas.
//  - KinematicTarget: a recorded angle trajectory, r_k = (model(t_k + offset) - data_k) / sigma,
//    with an optional time offset that is itself a fitted parameter.
#include <algorithm>
#include <string>
#include <vector>

#include "fit/kinematic_data.hpp"

namespace phasmid::fit {

struct FeatureTarget {
  std::string feature;  // e.g. "middle.fti.period_ms" (see docs/features.md)
  double value = 0;
  double tolerance = 1;  // in feature units; residual = (feature - value) / tolerance
  std::string origin;    // config file:line
};

struct SwitchCondition {
  std::string channel;   // "<leg>.<joint>"
  double time_ms = 0;    // T_sw
  double angle_deg = 0;  // gamma_e
  double angle_tolerance_deg = 1;
  double velocity_tolerance_deg_s = 0;      // > 0: residual velocity / tol (target 0)
  double acceleration_tolerance_deg_s2 = 0; // > 0: residual acceleration / tol (target 0), left limit at T_sw
  std::string origin;
};

struct KinematicTarget {
  KinematicData data;
  double sigma_deg = 1;             // measurement noise; residual = (model - data) / sigma
  double t_min_ms = 0;              // samples before this (model time) are ignored (transient)
  std::string time_offset_parameter;  // empty: no offset; else a fit parameter id (ms), model time = data time + offset
  std::string origin;
  std::string file;  // the recording read
};

// A recorded channel as a model output (PEtab's observable): data = sign * scale * model + offset
// (deg).
struct Observable {
  std::string data_channel;      // "L2.fti"
  std::string model_channel;     // "middle.fti"
  double sign = 1;               // +1 or -1
  std::string offset_parameter;  // a fit parameter (deg, lin scale); empty: offset_deg, fixed
  double offset_deg = 0;
  std::string scale_parameter;   // a fit parameter (1, lin scale); empty: scale, fixed
  double scale = 1;
  double sigma_deg = 0;          // > 0: the noise; 0: the recording's step-to-step SD per bin
  // A fit parameter (deg, any scale, lower bound > 0): one noise for all bins, estimated (or
  // the table's fixed value); overrides sigma_deg. The objective stays the negative
  // log-likelihood: its n ln(sigma) term enters as one more residual (docs/recordings.md).
  std::string sigma_parameter;
  std::string origin;
};

struct StepCycleTarget {
  features::StepCycles data;  // the recording's summary
  std::string leg, model_leg;  // "L2", "middle"
  std::vector<Observable> observables;
  double period_sigma_ms = 0, duty_factor_sigma = 0;  // 0: the recording's step-to-step SD
  double sigma_floor_deg = 0.5;  // lower bound of a per-bin SD taken from the recording
  double sample_ms = 2;          // spacing of the model outputs the profiles interpolate
  std::string condition;         // PEtab's simulationConditionId (fit/condition_problem.hpp); empty: none
  std::string origin, file;
  // The noises the residuals use where an observable gives none: the given sigma, else the
  // recording's step-to-step SD (per bin of channel c floored at sigma_floor_deg).
  double period_noise_ms() const { return period_sigma_ms > 0 ? period_sigma_ms : data.period_sd_ms; }
  double duty_factor_noise() const { return duty_factor_sigma > 0 ? duty_factor_sigma : data.duty_factor_sd; }
  double bin_sd_deg(size_t c, size_t k) const { return std::max(data.sd_deg[c][k], sigma_floor_deg); }
};

struct Targets {
  std::vector<FeatureTarget> features;
  std::vector<SwitchCondition> switches;
  std::vector<KinematicTarget> kinematics;
  std::vector<StepCycleTarget> step_cycles;
  bool empty() const { return features.empty() && switches.empty() && kinematics.empty() && step_cycles.empty(); }
};

}  // namespace phasmid::fit
