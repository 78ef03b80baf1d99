#include "features/joint_range.hpp"

#include <fmt/format.h>

#include <cmath>

#include "common/error.hpp"
#include "common/units.hpp"

namespace phasmid::features {
namespace {
bool admissible(double angle_rad) {
  const double deg = angle_rad * units::kDegPerRad;
  return deg >= kMinAdmissibleAngleDeg && deg <= kMaxAdmissibleAngleDeg;  // NaN fails too
}

void check_angle(const model::AngleChannel& ch, double t_ms, double angle_rad) {
  if (admissible(angle_rad)) return;
  const double deg = angle_rad * units::kDegPerRad;
  throw SolverError(fmt::format("joint {}.{} left its admissible range [{:g}, {:g}] deg at t = {:g} ms (angle {:g} deg)",
                                ch.leg, ch.joint, kMinAdmissibleAngleDeg, kMaxAdmissibleAngleDeg, t_ms, deg));
}
}  // namespace

void check_joint_ranges(const model::OdeModel& model, const solver::SolveResult& r) {
  for (const auto& ch : model.angles()) {
    for (size_t k = 0; k < r.t.size(); ++k) check_angle(ch, r.t[k], r.state(k, ch.angle_state));
    for (const auto& e : r.events) check_angle(ch, e.t, e.y.at(ch.angle_state));
  }
}

JointRangeWatch::JointRangeWatch(const model::OdeModel& model, solver::OutputSink& next)
    : model_(model), next_(next), first_outside_(model.angles().size(), {NAN, 0.0}) {}

void JointRangeWatch::record(double t, const double* y, size_t n) {
  const auto& angles = model_.angles();
  for (size_t c = 0; c < angles.size(); ++c)
    if (std::isnan(first_outside_[c].first) && !admissible(y[angles[c].angle_state])) first_outside_[c] = {t, y[angles[c].angle_state]};
  next_.record(t, y, n);
}

void JointRangeWatch::check(const solver::SolveResult& r) const {
  const auto& angles = model_.angles();
  for (size_t c = 0; c < angles.size(); ++c) {
    if (!std::isnan(first_outside_[c].first)) check_angle(angles[c], first_outside_[c].first, first_outside_[c].second);
    for (const auto& e : r.events) check_angle(angles[c], e.t, e.y.at(angles[c].angle_state));
  }
}

}  // namespace phasmid::features
