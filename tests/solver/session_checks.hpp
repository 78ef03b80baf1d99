#pragma once
// Checks the integrator sessions share (tests/solver/test_command_schedule.cpp for CVODES,
// test_dopri_session.cpp for Dormand-Prince): integrating towards 100 ms, the session stops at
// its stop time, 50 ms, exactly; roots of the harmonic oscillator in their directions.
#include <gtest/gtest.h>

#include <nvector/nvector_serial.h>

#include <cmath>

#include "solver/integrator_session.hpp"

namespace phasmid::test {

// Sets the stop at 50 ms and advances there; *t is the time reached. Returns the steps taken.
inline long advance_to_stop_at_50(solver::IntegratorSession& session, double* t) {
  session.set_stop_time(50.0);
  *t = 0.0;
  EXPECT_EQ(session.advance(100.0, t, CV_NORMAL), CV_TSTOP_RETURN);
  EXPECT_DOUBLE_EQ(*t, 50.0);
  const long steps = session.total_steps();
  EXPECT_GT(steps, 0);
  return steps;
}

// The harmonic oscillator y1 = cos t, y2 = -sin t from (1, 0), and two roots of y1 (for the
// directions -1 and +1: y1 falls through 0 at pi/2 and rises at 3 pi/2).
inline int oscillator_rhs(sunrealtype, N_Vector y, N_Vector ydot, void*) {
  NV_Ith_S(ydot, 0) = NV_Ith_S(y, 1);
  NV_Ith_S(ydot, 1) = -NV_Ith_S(y, 0);
  return 0;
}
inline int oscillator_roots(sunrealtype, N_Vector y, sunrealtype* gout, void*) {
  gout[0] = NV_Ith_S(y, 0);
  gout[1] = NV_Ith_S(y, 0);
  return 0;
}

// With the oscillator's roots initialised in directions (-1, +1) and a stop at 5: the two
// roots at pi/2 (falling) and 3 pi/2 (rising), within 1e-8. Returns the time reached.
inline double expect_oscillator_roots(solver::IntegratorSession& session) {
  double t = 0.0;
  int found[2] = {0, 0};
  EXPECT_EQ(session.advance(5.0, &t, CV_NORMAL), CV_ROOT_RETURN);
  session.root_info(found);
  EXPECT_NEAR(t, M_PI / 2, 1e-8);
  EXPECT_EQ(found[0], -1);
  EXPECT_EQ(found[1], 0);
  EXPECT_EQ(session.advance(5.0, &t, CV_NORMAL), CV_ROOT_RETURN);
  session.root_info(found);
  EXPECT_NEAR(t, 3 * M_PI / 2, 1e-8);
  EXPECT_EQ(found[1], 1);
  return t;
}

}  // namespace phasmid::test
