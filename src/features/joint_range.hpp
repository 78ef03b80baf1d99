#pragma once
// Admissible joint angles: a run whose joint angle leaves them has left the physics of the
// model (e.g. a viscosity or spring constant near 0 lets the angle swing through thousands of
// degrees), so its trajectory and features are not results. Every verb sees it the same way:
// simulate exits with the one-line error, a sweep records a failed point, a fit a failed
// evaluation (docs/model.md "Admissible ranges").
#include <utility>
#include <vector>

#include "model/ode_model.hpp"
#include "solver/output_sink.hpp"
#include "solver/simulator.hpp"

namespace phasmid::features {

// deg. The dissertation gives the extremal angles of walking (Tables A.14-A.23, 25-145 deg),
// not anatomical limits; each joint is a hinge between two segments, so a documented choice
// of the widest range a hinge angle can have: [-180, 180] deg.
inline constexpr double kMinAdmissibleAngleDeg = -180.0;
inline constexpr double kMaxAdmissibleAngleDeg = 180.0;

// Throws SolverError "joint middle.fti left its admissible range [-180, 180] deg at t = ... ms
// (angle ... deg)" if an angle state at any output time or event is outside the range.
void check_joint_ranges(const model::OdeModel& model, const solver::SolveResult& r);

// The same check for a run whose outputs go to a sink (SolverOptions::output_sink): watches
// them on their way to `next`; check(r) then throws what check_joint_ranges would have thrown
// on the whole trajectory (per joint: its first output outside the range, else its events).
class JointRangeWatch : public solver::OutputSink {
 public:
  JointRangeWatch(const model::OdeModel& model, solver::OutputSink& next);
  void record(double t, const double* y, size_t n) override;
  void check(const solver::SolveResult& r) const;

 private:
  const model::OdeModel& model_;
  solver::OutputSink& next_;
  std::vector<std::pair<double, double>> first_outside_;  // per angle: (t ms, angle rad); t NaN: none
};

}  // namespace phasmid::features
