#pragma once
// Shared by the feature-sensitivity tests: forward sensitivities next to central finite
// differences at two steps (h and 2h), so that a test compares only where the difference
// quotient is well conditioned (the two steps agree).
#include <cmath>

#include "sensitivity/sensitivity.hpp"

namespace phasmid::sensitivity_test {

// Options of a feature-sensitivity comparison: features only (no trajectory), 5 ms output grid.
inline sensitivity::SensitivityOptions feature_options(std::vector<std::string> parameters, double t_end_ms,
                                                       double discard_ms) {
  sensitivity::SensitivityOptions o;
  o.parameters = std::move(parameters);
  o.t_end_ms = t_end_ms;
  o.discard_ms = discard_ms;
  o.output_dt_ms = 5;
  o.write_trajectory = false;
  return o;
}

struct ForwardAndFd {
  sensitivity::SensitivityReport fwd, fd, fd2;
};

// Forward at rtol = atol = rtol_forward; central differences at rtol_fd with relative steps h, 2h.
inline ForwardAndFd forward_and_fd(const model::OdeModel& m, sensitivity::SensitivityOptions o, double rtol_forward,
                                   double rtol_fd, double h) {
  ForwardAndFd r;
  const auto p = m.parameters().values();
  o.solver.rtol = o.solver.atol = rtol_forward;
  r.fwd = sensitivity::analyse_sensitivities(m, p, o);
  o.method = sensitivity::Method::FiniteDifference;
  o.solver.rtol = o.solver.atol = rtol_fd;
  o.fd_relative_step = h;
  r.fd = sensitivity::analyse_sensitivities(m, p, o);
  o.fd_relative_step = 2 * h;
  r.fd2 = sensitivity::analyse_sensitivities(m, p, o);
  return r;
}

// The difference quotient of feature f by parameter j does not depend on the step: the
// quotients at h and 2h agree to 0.25 % (otherwise event-time noise or a kink dominates it).
inline bool fd_steps_agree(const sensitivity::SensitivityReport& fd, const sensitivity::SensitivityReport& fd2,
                           size_t f, size_t j) {
  // Written as !(differ) so that a NaN quotient counts as agreeing and fails the comparison.
  return !(std::abs(fd.absolute(f, j) - fd2.absolute(f, j)) > 0.0025 * std::abs(fd.absolute(f, j)));
}

}  // namespace phasmid::sensitivity_test
