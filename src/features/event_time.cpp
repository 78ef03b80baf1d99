#include "features/event_time.hpp"

#include <cmath>

#include "common/error.hpp"

namespace phasmid::features {

Eigen::VectorXd event_time_sensitivity(const solver::Event& e, const solver::RootSpec& root, size_t ns) {
  Eigen::VectorXd dt(ns);
  if (ns == 0) return dt;
  if (e.s.size() != e.y.size() * ns) throw Error("internal: event without state sensitivities");
  const double gdot = e.ydot.at(root.state);  // dg/dy . f
  if (gdot == 0.0 || !std::isfinite(gdot))
    throw Error("event at t = " + std::to_string(e.t) + " ms is a tangential crossing: its time is not differentiable");
  for (size_t j = 0; j < ns; ++j) dt[j] = -e.s[root.state * ns + j] / gdot;
  return dt;
}

Eigen::VectorXd state_at_event_sensitivity(const solver::Event& e, size_t i, const Eigen::VectorXd& dt_dp) {
  const size_t ns = static_cast<size_t>(dt_dp.size());
  Eigen::VectorXd d(ns);
  for (size_t j = 0; j < ns; ++j) d[j] = e.s[i * ns + j] + e.ydot[i] * dt_dp[j];
  return d;
}

}  // namespace phasmid::features
