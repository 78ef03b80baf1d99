#include "features/joint_range.hpp"

#include <fmt/format.h>

#include "common/error.hpp"
#include "common/units.hpp"

namespace phasmid::features {
namespace {
void check_angle(const model::AngleChannel& ch, double t_ms, double angle_rad) {
  const double deg = angle_rad * units::kDegPerRad;
  if (deg >= kMinAdmissibleAngleDeg && deg <= kMaxAdmissibleAngleDeg) return;  // NaN fails too
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

}  // namespace phasmid::features
