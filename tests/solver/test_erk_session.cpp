// ARKODE's explicit Runge-Kutta integrator behind the session interface (solver/erk_session.hpp):
// the closed form of y' = -k y across a restart, roots of the harmonic oscillator at pi/2 and
// 3 pi/2, and a middle leg whose direction switch is triggered by events, integrated with
// Dormand-Prince 5(4) as one system and per joint, against CVODES BDF at rtol 1e-10.
#include <gtest/gtest.h>

#include <nvector/nvector_serial.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "config/config.hpp"
#include "features/features.hpp"
#include "middle_leg_trigger_config.hpp"
#include "session_checks.hpp"
#include "solver/cvodes_session.hpp"
#include "solver/erk_session.hpp"
#include "solver/integrator_kind.hpp"

using namespace phasmid;

TEST(ErkSession, DecayMatchesTheClosedFormAcrossARestart) {
  for (auto kind : {solver::IntegratorKind::ErkDp5, solver::IntegratorKind::ErkVerner65, solver::IntegratorKind::ErkBs3}) {
    solver::SolverOptions so;
    so.integrator = kind;
    so.rtol = so.atol = 1e-10;
    double k = 0.02;
    auto rhs = [](sunrealtype, N_Vector y, N_Vector ydot, void* ud) {
      NV_Ith_S(ydot, 0) = -*static_cast<const double*>(ud) * NV_Ith_S(y, 0);
      return 0;
    };
    solver::SundialsContext ctx;
    const double y0 = 3.0;
    solver::ErkSession session(ctx.get(), so, &y0, 1, rhs, &k);
    double t = 0.0;
    const long steps_before = test::advance_to_stop_at_50(session, &t);
    k = 0.05;  // the right-hand side switches at 50 ms
    session.restart(t);
    EXPECT_EQ(session.total_steps(), steps_before);  // counted over the restart
    session.set_stop_time(100.0);
    EXPECT_GE(session.advance(100.0, &t, CV_NORMAL), 0);
    EXPECT_DOUBLE_EQ(t, 100.0);
    const std::string name = solver::integrator_name(kind);
    EXPECT_NEAR(NV_Ith_S(session.y(), 0), 3.0 * std::exp(-0.02 * 50.0 - 0.05 * 50.0), 1e-8) << name;
    EXPECT_GT(session.total_steps(), steps_before);
    EXPECT_EQ(session.stats().steps, session.total_steps());
    EXPECT_GT(session.stats().rhs_evals, 3 * session.total_steps()) << name;  // at least 4 stages per step
  }
}

// y1 = cos t, y2 = -sin t: y1 falls through 0 at pi/2 and rises at 3 pi/2.
TEST(ErkSession, LocatesRootsInTheirDirection) {
  solver::SolverOptions so;
  so.integrator = solver::IntegratorKind::ErkDp5;
  so.rtol = so.atol = 1e-10;
  solver::SundialsContext ctx;
  const double y0[2] = {1.0, 0.0};
  solver::ErkSession session(ctx.get(), so, y0, 2, test::oscillator_rhs, nullptr);
  session.init_roots({-1, +1}, test::oscillator_roots);
  session.set_stop_time(5.0);
  double t = test::expect_oscillator_roots(session);
  // The interpolant's derivative at the root: y1' = -sin(3 pi / 2) = 1.
  N_Vector d = session.work();
  ASSERT_GE(session.dky(t, 1, d), 0);
  EXPECT_NEAR(NV_Ith_S(d, 0), 1.0, 1e-6);
  EXPECT_GE(session.advance(5.0, &t, CV_NORMAL), 0);  // success or stop time: tout is the stop
  EXPECT_DOUBLE_EQ(t, 5.0);
  EXPECT_NEAR(NV_Ith_S(session.y(), 0), std::cos(5.0), 1e-8);
  EXPECT_EQ(session.flag_name(-1), "ARK_TOO_MUCH_WORK");
}

TEST(ErkSession, NamesTheIntegrators) {
  EXPECT_EQ(solver::integrator_from_name("erk_dp5"), solver::IntegratorKind::ErkDp5);
  EXPECT_EQ(solver::integrator_from_name("cvodes_bdf"), solver::IntegratorKind::Bdf);
  EXPECT_FALSE(solver::integrator_from_name("rk4"));
  for (auto kind : {solver::IntegratorKind::Bdf, solver::IntegratorKind::Adams, solver::IntegratorKind::ErkBs3,
                    solver::IntegratorKind::ErkDp5, solver::IntegratorKind::ErkVerner65,
                    solver::IntegratorKind::ErkFehlberg78})
    EXPECT_EQ(solver::integrator_from_name(solver::integrator_name(kind)), kind);
  auto cfg = config::parse_config("[model]\ntype = \"single_joint\"\n[simulation]\nintegrator = \"rk4\"\n", "x.toml");
  try {
    config::simulation_settings(cfg);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("\"dopri5\""), std::string::npos) << e.what();
  }
}

namespace {
struct TriggerRun {
  std::unique_ptr<model::OdeModel> m;
  solver::SolveResult r;
};

// The direction switch of tests/solver/test_command_triggers.cpp: backward at the first
// touch-down after 1500 ms, forward 200 ms after the next lift-off; 3 s.
TriggerRun run_switch(solver::IntegratorKind kind, bool partitioned, double rtol) {
  auto cfg = config::parse_config(test::middle_leg_trigger_config(1500, 200), "triggers.toml");
  TriggerRun x;
  x.m = config::build_model(cfg, {});
  solver::SolverOptions o = config::simulation_settings(cfg).solver;
  o.integrator = kind;
  o.partitioning = partitioned ? solver::Partitioning::On : solver::Partitioning::Off;
  o.rtol = o.atol = rtol;
  solver::Simulator sim(*x.m, o);
  x.r = sim.run(x.m->parameters().values(), solver::output_grid(3000, 5.0), features::feature_roots(*x.m));
  return x;
}
}  // namespace

// Events, the restarts at triggered commands and the partitioned driver's interpolation of the
// other joints' angles all run on ERKStep: command times and every event time within 0.01 ms
// of CVODES BDF at rtol 1e-10, and the output trajectory within 0.01 deg of the angles.
TEST(ErkSession, TriggeredDirectionSwitchMatchesTheTightBdfRun) {
  const TriggerRun ref = run_switch(solver::IntegratorKind::Bdf, false, 1e-10);
  ASSERT_EQ(ref.r.commands.size(), 2u);
  for (bool partitioned : {false, true}) {
    const TriggerRun erk = run_switch(solver::IntegratorKind::ErkDp5, partitioned, 1e-8);
    EXPECT_EQ(erk.r.stats.jac_evals, 0);
    EXPECT_EQ(erk.r.stats.integrators > 1, partitioned);
    ASSERT_EQ(erk.r.commands.size(), 2u);
    for (size_t c = 0; c < 2; ++c) {
      std::printf("%s: command %zu at %.5f ms (BDF 1e-10: %.5f ms)\n", partitioned ? "partitioned" : "whole", c,
                  erk.r.commands[c].t_ms, ref.r.commands[c].t_ms);
      EXPECT_NEAR(erk.r.commands[c].t_ms, ref.r.commands[c].t_ms, 0.01);
    }
    ASSERT_EQ(erk.r.events.size(), ref.r.events.size());
    double worst = 0.0;
    for (size_t e = 0; e < ref.r.events.size(); ++e) {
      EXPECT_EQ(erk.r.events[e].root, ref.r.events[e].root) << e;
      worst = std::max(worst, std::abs(erk.r.events[e].t - ref.r.events[e].t));
    }
    std::printf("%s: %zu events, largest time difference %.2e ms\n", partitioned ? "partitioned" : "whole",
                ref.r.events.size(), worst);
    EXPECT_LT(worst, 0.01);
  }
}
