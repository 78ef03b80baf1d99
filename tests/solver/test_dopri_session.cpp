// phasmid's own Dormand-Prince 5(4) stepper (solver/dopri_session.hpp): the closed form of
// y' = -k y across a restart, roots of the harmonic oscillator in their directions,
// convergence on van der Pol's oscillator against CVODES BDF, the failure flags, and the
// middle leg's triggered direction switch as one system and per joint against CVODES BDF.
#include <gtest/gtest.h>

#include <nvector/nvector_serial.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "features/features.hpp"
#include "middle_leg_trigger_config.hpp"
#include "session_checks.hpp"
#include "solver/dopri_session.hpp"
#include "solver/integrator_kind.hpp"
#include "solver/cvodes_session.hpp"

using namespace phasmid;

namespace {

solver::SolverOptions dopri(double tol) {
  solver::SolverOptions so;
  so.integrator = solver::IntegratorKind::Dopri5;
  so.rtol = so.atol = tol;
  return so;
}

int decay_rhs(sunrealtype, N_Vector y, N_Vector ydot, void* ud) {
  NV_Ith_S(ydot, 0) = -*static_cast<const double*>(ud) * NV_Ith_S(y, 0);
  return 0;
}

// Van der Pol's oscillator, mu = 5: slow drifts and fast jumps, so the controller both grows
// and cuts the step.
int van_der_pol(sunrealtype, N_Vector y, N_Vector ydot, void*) {
  const double x = NV_Ith_S(y, 0), v = NV_Ith_S(y, 1);
  NV_Ith_S(ydot, 0) = v;
  NV_Ith_S(ydot, 1) = 5.0 * (1 - x * x) * v - x;
  return 0;
}

// The harmonic oscillator from (1, 0) with its two roots (directions -1, +1) and a stop at 5.
std::unique_ptr<solver::DopriSession> oscillator_session(SUNContext ctx, double tol) {
  const double y0[2] = {1.0, 0.0};
  auto session = std::make_unique<solver::DopriSession>(ctx, dopri(tol), y0, 2, test::oscillator_rhs, nullptr);
  session->init_roots({-1, +1}, test::oscillator_roots);
  session->set_stop_time(5.0);
  return session;
}

}  // namespace

TEST(DopriSession, DecayMatchesTheClosedFormAcrossARestart) {
  double k = 0.02;
  solver::SundialsContext ctx;
  const double y0 = 3.0;
  solver::DopriSession session(ctx.get(), dopri(1e-10), &y0, 1, decay_rhs, &k);
  double t = 0.0;
  const long steps_before = test::advance_to_stop_at_50(session, &t);
  EXPECT_NEAR(NV_Ith_S(session.y(), 0), 3.0 * std::exp(-1.0), 1e-9);
  k = 0.05;  // the right-hand side switches at 50 ms
  session.restart(t);
  EXPECT_EQ(session.total_steps(), steps_before);
  N_Vector slope = session.work();  // the new slope at once, before any step
  ASSERT_EQ(session.dky(t, 1, slope), 0);
  EXPECT_NEAR(NV_Ith_S(slope, 0), -0.05 * NV_Ith_S(session.y(), 0), 1e-15);
  session.set_stop_time(100.0);
  EXPECT_EQ(session.advance(100.0, &t, CV_NORMAL), CV_SUCCESS);  // tout first, as CVODES
  EXPECT_DOUBLE_EQ(t, 100.0);
  EXPECT_NEAR(NV_Ith_S(session.y(), 0), 3.0 * std::exp(-0.02 * 50.0 - 0.05 * 50.0), 1e-9);
  EXPECT_GT(session.total_steps(), steps_before);
  // Six right-hand sides per attempt; at each of the two starts the slope and one to four
  // (up to 16 with failing slopes) for the first step's estimate.
  const solver::SolverStats s = session.stats();
  const long starts = s.rhs_evals - 6 * (s.steps + s.error_test_failures);
  EXPECT_GE(starts, 4);
  EXPECT_LE(starts, 10);
}

TEST(DopriSession, LocatesRootsInTheirDirectionAndInterpolates) {
  solver::SundialsContext ctx;
  auto owner = oscillator_session(ctx.get(), 1e-10);
  solver::DopriSession& session = *owner;
  double t = test::expect_oscillator_roots(session);
  EXPECT_NEAR(NV_Ith_S(session.y(), 1), 1.0, 1e-8);  // y2 = -sin(3 pi / 2)
  // The interpolant and its derivatives at the root: y1' = 1, y1'' = -y1 = 0, y1''' = -y1' = -1.
  N_Vector d = session.work();
  const double expected[4] = {0.0, 1.0, 0.0, -1.0}, within[4] = {1e-8, 1e-7, 1e-3, 0.05};
  for (int k = 0; k < 4; ++k) {
    ASSERT_EQ(session.dky(t, k, d), 0);
    EXPECT_NEAR(NV_Ith_S(d, 0), expected[k], within[k]) << "derivative " << k;
  }
  EXPECT_LT(session.dky(session.current_time() + 1.0, 0, d), 0);  // outside the last step
  EXPECT_EQ(session.advance(5.0, &t, CV_NORMAL), CV_SUCCESS);      // tout reached before the stop
  EXPECT_DOUBLE_EQ(t, 5.0);
  EXPECT_NEAR(NV_Ith_S(session.y(), 0), std::cos(5.0), 1e-8);
}

// Van der Pol's oscillator at seven tolerances against CVODES BDF at 1e-12: the solution at
// 30 within a few thousand times the tolerance, and the step count growing as the tolerance
// tightens, by about the fifth root of the ratio (ARKODE's Dormand-Prince took the same steps
// to 0.04 %, docs/solver.md "Integrators").
TEST(DopriSession, ConvergesOnVanDerPol) {
  solver::SundialsContext ctx;
  const double y0[2] = {2.0, 0.0};
  solver::SolverOptions bdf;
  bdf.rtol = bdf.atol = 1e-12;
  solver::CvodesSession ref(ctx.get(), bdf, y0, 2, van_der_pol, nullptr);
  ref.set_linear_solver(solver::LinearSystem::Dense, 0, 0, nullptr);
  ref.set_stop_time(30.0);
  double t_ref = 0;
  ASSERT_EQ(ref.advance(40.0, &t_ref, CV_NORMAL), CV_TSTOP_RETURN);
  long previous_steps = 0;
  for (double tol : {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10}) {
    solver::DopriSession ours(ctx.get(), dopri(tol), y0, 2, van_der_pol, nullptr);
    ours.set_stop_time(30.0);
    double t = 0;
    ASSERT_EQ(ours.advance(40.0, &t, CV_NORMAL), CV_TSTOP_RETURN);
    EXPECT_DOUBLE_EQ(t, 30.0);
    std::printf("tol %g: %ld steps, x(30) %.10f (BDF 1e-12: %.10f)\n", tol, ours.total_steps(), NV_Ith_S(ours.y(), 0),
                NV_Ith_S(ref.y(), 0));
    EXPECT_NEAR(NV_Ith_S(ours.y(), 0), NV_Ith_S(ref.y(), 0), 2000 * tol) << tol;
    if (previous_steps > 0) {
      EXPECT_GT(ours.total_steps(), 1.3 * previous_steps) << tol;  // 10^(1/5) = 1.58
      EXPECT_LT(ours.total_steps(), 2.0 * previous_steps) << tol;
    }
    previous_steps = ours.total_steps();
  }
}

TEST(DopriSession, OneStepModeReturnsAfterEachStep) {
  solver::SundialsContext ctx;
  const double y0[2] = {2.0, 0.0};
  solver::DopriSession session(ctx.get(), dopri(1e-6), y0, 2, van_der_pol, nullptr);
  session.set_stop_time(1.0);
  double t = 0.0;
  for (long n = 1; n <= 3; ++n) {
    ASSERT_EQ(session.advance(1.0, &t, CV_ONE_STEP), CV_SUCCESS);
    EXPECT_EQ(session.total_steps(), n);
    EXPECT_DOUBLE_EQ(t, session.current_time());
    EXPECT_GT(session.last_step(), 0.0);
  }
  int flag = CV_SUCCESS;
  while (flag == CV_SUCCESS) flag = session.advance(1.0, &t, CV_ONE_STEP);
  EXPECT_EQ(flag, CV_TSTOP_RETURN);
  EXPECT_DOUBLE_EQ(t, 1.0);
  EXPECT_DOUBLE_EQ(session.current_time(), 1.0);  // the last step lands on the stop exactly
}

// After a root inside a step, one-step mode first returns that step's end, as CVODES does.
TEST(DopriSession, OneStepModeFinishesTheStepOfARoot) {
  solver::SundialsContext ctx;
  auto owner = oscillator_session(ctx.get(), 1e-8);
  solver::DopriSession& session = *owner;
  double t = 0.0;
  int flag = CV_SUCCESS;
  while (flag == CV_SUCCESS) flag = session.advance(5.0, &t, CV_ONE_STEP);
  ASSERT_EQ(flag, CV_ROOT_RETURN);
  EXPECT_NEAR(t, M_PI / 2, 1e-8);
  const long steps = session.total_steps();
  const double end = session.current_time();
  ASSERT_GT(end, t);
  EXPECT_EQ(session.advance(5.0, &t, CV_ONE_STEP), CV_SUCCESS);
  EXPECT_EQ(t, end);
  EXPECT_EQ(session.total_steps(), steps);
  EXPECT_NEAR(NV_Ith_S(session.y(), 0), std::cos(end), 1e-7);
  EXPECT_EQ(session.advance(5.0, &t, CV_ONE_STEP), CV_SUCCESS);  // then steps again
  EXPECT_EQ(session.total_steps(), steps + 1);
}

TEST(DopriSession, ReportsFailuresWithTheirFlags) {
  solver::SundialsContext ctx;
  const double y0[2] = {2.0, 0.0};
  {  // a stop time behind the current time
    solver::DopriSession session(ctx.get(), dopri(1e-6), y0, 2, van_der_pol, nullptr);
    double t = 0;
    session.set_stop_time(1.0);
    ASSERT_EQ(session.advance(2.0, &t, CV_NORMAL), CV_TSTOP_RETURN);
    session.set_stop_time(0.5);
    const int flag = session.advance(2.0, &t, CV_NORMAL);
    EXPECT_EQ(flag, -22);
    EXPECT_NE(session.flag_name(flag).find("ILL_INPUT"), std::string::npos);
  }
  {  // more steps than max_steps in one call
    solver::SolverOptions so = dopri(1e-10);
    so.max_steps = 10;
    solver::DopriSession session(ctx.get(), so, y0, 2, van_der_pol, nullptr);
    double t = 0;
    const int flag = session.advance(30.0, &t, CV_NORMAL);
    EXPECT_EQ(flag, -1);
    EXPECT_EQ(session.total_steps(), 10);
    EXPECT_EQ(session.flag_name(flag), "TOO_MUCH_WORK");
  }
  {  // a right-hand side that fails recoverably beyond t = 1: rejected down to the time's resolution
    auto failing = [](sunrealtype t, N_Vector, N_Vector ydot, void*) {
      NV_Ith_S(ydot, 0) = 1.0;
      return t > 1.0 ? 1 : 0;
    };
    const double z = 0.0;
    solver::DopriSession session(ctx.get(), dopri(1e-6), &z, 1, failing, nullptr);
    double t = 0;
    const int flag = session.advance(2.0, &t, CV_NORMAL);
    EXPECT_EQ(flag, -3);
    EXPECT_EQ(session.flag_name(flag), "ERR_FAILURE");
    EXPECT_LE(t, 1.0);
    EXPECT_GT(t, 0.99);
    EXPECT_NEAR(NV_Ith_S(session.y(), 0), t, 1e-12);  // y = t: the steps before stay valid
  }
  {  // an unrecoverable failure
    auto broken = [](sunrealtype, N_Vector, N_Vector, void*) { return -1; };
    const double z = 0.0;
    solver::DopriSession session(ctx.get(), dopri(1e-6), &z, 1, broken, nullptr);
    double t = 0;
    EXPECT_EQ(session.advance(2.0, &t, CV_NORMAL), -8);
  }
}

TEST(DopriSession, IsNamedDopri5) {
  EXPECT_EQ(solver::integrator_from_name("dopri5"), solver::IntegratorKind::Dopri5);
  EXPECT_EQ(solver::integrator_name(solver::IntegratorKind::Dopri5), "dopri5");
  EXPECT_TRUE(solver::is_explicit_rk(solver::IntegratorKind::Dopri5));
  EXPECT_FALSE(solver::is_explicit_rk(solver::IntegratorKind::Bdf));
  EXPECT_EQ(solver::integrator_from_name("cvodes_bdf"), solver::IntegratorKind::Bdf);
  // The integrators of the method study that were removed are unknown names now.
  for (const char* removed : {"cvodes_adams", "erk_bs3", "erk_dp5", "erk_verner65", "erk_fehlberg78"})
    EXPECT_FALSE(solver::integrator_from_name(removed)) << removed;
  EXPECT_EQ(solver::integrator_names(), "\"cvodes_bdf\", \"dopri5\"");
}

namespace {
// The direction switch of tests/solver/test_command_triggers.cpp: backward at the first
// touch-down after 1500 ms, forward 200 ms after the next lift-off; 3 s.
solver::SolveResult run_switch(solver::IntegratorKind kind, bool partitioned, double rtol,
                               std::unique_ptr<model::OdeModel>& m) {
  auto cfg = config::parse_config(test::middle_leg_trigger_config(1500, 200), "triggers.toml");
  m = config::build_model(cfg, {});
  solver::SolverOptions o = config::simulation_settings(cfg).solver;
  o.integrator = kind;
  o.partitioning = partitioned ? solver::Partitioning::On : solver::Partitioning::Off;
  o.rtol = o.atol = rtol;
  solver::Simulator sim(*m, o);
  return sim.run(m->parameters().values(), solver::output_grid(3000, 5.0), features::feature_roots(*m));
}
}  // namespace

// Events, restarts at triggered commands and the partitioned driver's coupling polynomials on
// this stepper: command and event times within 0.01 ms of CVODES BDF at rtol 1e-10.
TEST(DopriSession, TriggeredDirectionSwitchMatchesTheTightBdfRun) {
  std::unique_ptr<model::OdeModel> m_ref, m;
  const solver::SolveResult ref = run_switch(solver::IntegratorKind::Bdf, false, 1e-10, m_ref);
  ASSERT_EQ(ref.commands.size(), 2u);
  for (bool partitioned : {false, true}) {
    const solver::SolveResult r = run_switch(solver::IntegratorKind::Dopri5, partitioned, 1e-8, m);
    EXPECT_EQ(r.stats.integrators > 1, partitioned);
    ASSERT_EQ(r.commands.size(), 2u);
    for (size_t c = 0; c < 2; ++c) EXPECT_NEAR(r.commands[c].t_ms, ref.commands[c].t_ms, 0.01) << c;
    ASSERT_EQ(r.events.size(), ref.events.size());
    double worst = 0.0;
    for (size_t e = 0; e < ref.events.size(); ++e) {
      EXPECT_EQ(r.events[e].root, ref.events[e].root) << e;
      EXPECT_EQ(r.events[e].direction, ref.events[e].direction) << e;
      worst = std::max(worst, std::abs(r.events[e].t - ref.events[e].t));
    }
    std::printf("%s: %zu events, largest time difference %.2e ms\n", partitioned ? "partitioned" : "whole",
                ref.events.size(), worst);
    EXPECT_LT(worst, 0.01);
  }
}
