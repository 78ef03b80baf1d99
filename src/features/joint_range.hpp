#pragma once
// Admissible joint angles: a run whose joint angle leaves them has left the physics of the
// model (e.g. a viscosity or spring constant near 0 lets the angle swing through thousands of
// degrees), so its trajectory and features are not results. Every verb sees it the same way:
// simulate exits with the one-line error, a sweep records a failed point, a fit a failed
// evaluation (docs/model.md "Admissible ranges").
#include "model/ode_model.hpp"
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

}  // namespace phasmid::features
