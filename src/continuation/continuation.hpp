#pragma once
// Pseudo-arclength continuation of periodic orbits in one parameter (docs/continuation.md).
// Each point of the branch is a cycle (y0 on the Poincare section, period T, parameter lambda)
// solved by Newton shooting (continuation/shooting.hpp) with the arclength condition
// t . W (z - z_pred) = 0 on z = (y0, T, lambda), W a diagonal scaling that measures a step in
// the parameter's unit (T relative to the first period and each state relative to its range
// over the first cycle, both across the whole parameter range). Predictor: the tangent (the
// null vector of Newton's matrix without the arclength row), oriented along the secant of the
// last two points; the step grows after quick convergence and halves after a failure.
// At each point: period, tracked features (features::compute_features on three periods of the
// converged cycle, as `phasmid features` computes them), all Floquet multipliers, stability.
// Between points: a fold (the tangent's lambda component changes sign), period doubling (a
// real multiplier through -1), torus (a complex pair through the unit circle) are located by
// secant iterations on a test function along the arc; a real multiplier through +1 without a
// fold is reported as a branch point. The branch ends at the range end, at max_points, where
// the period grows without bound, where the amplitude shrinks to zero (Hopf-like; the Hopf
// parameter extrapolated from amplitude^2, linear in lambda near a Hopf point), or where
// integration or Newton fails at the minimum step.
#include <algorithm>
#include <complex>
#include <functional>
#include <string>
#include <vector>

#include "continuation/shooting.hpp"

namespace phasmid::continuation {

struct ContinuationOptions {
  std::string parameter;  // the continuation parameter's name
  double start = 0.0, end = 0.0;  // range; the branch starts at `start` and heads for `end`
  // Parameters moved with it, linearly: `from` at start, `to` at end (e.g. both LD drives).
  struct Linked {
    std::string name;
    double from = 0.0, to = 0.0;
  };
  std::vector<Linked> linked;
  double initial_step = 0.0, min_step = 0.0, max_step = 0.0;  // arclength, in the parameter's unit
  int max_points = 100;
  std::vector<std::string> features;  // tracked features; empty: every feature the cycle gives
  ShootingOptions shooting;
  double feature_cycles = 3.0;        // periods integrated for the features of a point
  double max_period_factor = 10.0;    // "period_unbounded" once T exceeds this times the first period
  double hopf_amplitude_fraction = 0.05;  // "hopf" once the amplitude falls below this fraction of the largest
  int locate_iterations = 8;          // secant iterations that locate a special point
  // Called with the branch so far after each new point (its last point is the new one; the
  // progress lines and the partial file of the verb); may be empty.
  std::function<void(const struct Branch&)> on_point;
};

struct BranchPoint {
  double parameter = 0.0, period_ms = 0.0;
  double amplitude = 0.0;  // root-sum-square of each state's range over one period (state units)
  std::vector<double> y0;
  std::vector<std::complex<double>> multipliers;  // all, by decreasing modulus
  size_t trivial = 0;      // index of the multiplier closest to 1 (the phase direction)
  // Indices of further multipliers within ShootingOptions::neutral_tolerance of 1 (neutral
  // directions of a family of cycles); empty where that tolerance is 0.
  std::vector<size_t> neutral;
  bool stable = false;     // every multiplier but the trivial and neutral ones inside the unit circle
  // Whether multiplier i takes part in the stability and special-point tests.
  bool counted(size_t i) const { return i != trivial && std::find(neutral.begin(), neutral.end(), i) == neutral.end(); }
  std::vector<double> features;  // per tracked feature, NaN where the cycle gives none
  int newton_iterations = 0;
  double residual = 0.0;   // max |y(T) - y0|
  double tangent_parameter = 0.0;  // d lambda / ds along the branch direction
};

struct SpecialPoint {
  size_t index = 0;  // the branch point at or just after it
  std::string kind;  // fold, period_doubling, torus, branch_point, hopf, period_unbounded,
                     // integration_failure, no_convergence, range_end, max_points
  double parameter = 0.0, period_ms = 0.0;
  std::string note;  // one line: how it was found
};

struct Branch {
  std::string parameter, parameter_unit;
  std::vector<std::string> feature_names, feature_units;
  std::vector<BranchPoint> points;
  std::vector<SpecialPoint> special;  // in branch order; the last one says how the branch ended
  solver::RootSpec section{0, 0.0, 0};
  std::vector<HeldPhase> held_phases;  // with the fractions held along the branch
  std::string start_note;  // how the first cycle converged (residual, Newton iterations)
  long shots = 0;         // integrations with sensitivities (monodromy; all tries)
  long plain_shots = 0;   // integrations without (the quasi-Newton residuals)
  double seconds = 0.0;   // wall time
};

// Steps left at 0 take their defaults: min_step = |range|/1e5, initial_step = |range|/50,
// max_step = |range|/10 (the config refuses a step <= 0, so 0 means "left out").
void fill_default_steps(ContinuationOptions& o);

// Throws Error if no cycle is found at `start` or the options are inconsistent.
Branch continue_cycles(const model::OdeModel& model, std::vector<double> p, const ContinuationOptions& options);

// Kinds a special point may have, with one line each (docs/continuation.md; the HDF5 file
// stores the kind names).
const std::vector<std::pair<std::string, std::string>>& special_point_kinds();

}  // namespace phasmid::continuation
