// Solver pieces on their own: the CommandSchedule (stops, switch-time derivatives, triggered
// command times, sensitivity jumps) against values worked out by hand for a one-state model,
// and a CvodesSession against the closed form of y' = -k y.
#include <gtest/gtest.h>

#include <nvector/nvector_serial.h>

#include <cmath>

#include "common/error.hpp"
#include "solver/command_schedule.hpp"
#include "solver/cvodes_session.hpp"
#include "../rising_trigger.hpp"
#include "session_checks.hpp"

using namespace phasmid;

namespace {

// y' = a1 - k y before the command time tau, a2 - k y after; a second switch at 2 tau + 10
// (to 0 - k y) and two breakpoints outside the run that the schedule drops. A trigger on
// y rising through p[level] sets p[late] to the crossing time + 5 ms.
class TwoSwitches : public model::OdeModelT<TwoSwitches> {
 public:
  TwoSwitches() {
    params_.add({"s.a1", 2.0, "1/ms", "test", "drive before the command"});
    params_.add({"s.a2", 0.5, "1/ms", "test", "drive after the command"});
    params_.add({"s.k", 0.01, "1/ms", "test", "decay rate"});
    params_.add({"s.tau", 120.0, "ms", "test", "command time"});
    params_.add({"s.level", 40.0, "1", "test", "trigger threshold"});
    params_.add({"s.late", 300.0, "ms", "test", "triggered command time"});
    add_state("s.y", "1");
    model::CommandTrigger tr = test::rising_trigger("s.rise", 5, 0, 4, 5.0);
    tr.debounce_ms = 0.0;
    triggers_ = {tr};
  }
  std::string kind() const override { return "two_switches"; }
  std::vector<double> initial_state(const std::vector<double>&) const override { return {30.0}; }
  std::vector<double> breakpoints(const std::vector<double>& p, double) const override {
    return {2 * p[3] + 10, -5.0, p[3], p[5], 1e9};
  }
  template <class T>
  void eval(double t, const T* y, const T* p, T* ydot) const {
    const T drive = t < model::value_of(p[3]) ? p[0] : t < 2 * model::value_of(p[3]) + 10 ? p[1] : T(0.0);
    ydot[0] = drive - p[2] * y[0];
  }
};

}  // namespace

TEST(CommandSchedule, StopsAreTheBreakpointsInsideTheRunThenTheEnd) {
  TwoSwitches m;
  solver::CommandSchedule s(m, m.parameters().values(), 500.0, {3, 0});
  // The triggered time p[5] is "never" until its event: not a stop.
  EXPECT_EQ(s.p()[5], model::kUnresolvedMs);
  EXPECT_DOUBLE_EQ(s.next_stop(), 120.0);
  EXPECT_NEAR(s.next_stop_jump()[0], 1.0, 1e-7);  // d tau / d tau
  EXPECT_EQ(s.next_stop_jump()[1], 0.0);         // does not move with a1
  s.pass_stop();
  EXPECT_DOUBLE_EQ(s.next_stop(), 250.0);
  EXPECT_NEAR(s.next_stop_jump()[0], 2.0, 1e-7);  // d (2 tau + 10) / d tau
  EXPECT_FALSE(s.last_stop());
  s.pass_stop();
  EXPECT_DOUBLE_EQ(s.next_stop(), 500.0);
  EXPECT_TRUE(s.last_stop());
  EXPECT_DOUBLE_EQ(s.t_end(), 500.0);
}

TEST(CommandSchedule, TriggeredTimeIsNoSensitivityParameter) {
  TwoSwitches m;
  EXPECT_THROW(solver::CommandSchedule(m, m.parameters().values(), 500.0, {5}), Error);
}

TEST(CommandSchedule, TriggerRootsFollowTheCallersAndFireOnce) {
  TwoSwitches m;
  solver::CommandSchedule s(m, m.parameters().values(), 500.0, {3});
  const auto roots = s.roots({{0, 1.0, -1}});
  ASSERT_EQ(roots.size(), 2u);
  EXPECT_EQ(roots[1].state, 0u);
  EXPECT_DOUBLE_EQ(roots[1].level, 40.0);
  EXPECT_EQ(roots[1].direction, 0);  // both directions, for the debounce
  std::vector<solver::ResolvedCommand> commands;
  const double y = 40.0;
  EXPECT_FALSE(s.fire(0, 50.0, -1, &y, commands));  // falling: not the trigger's direction
  EXPECT_TRUE(s.fire(0, 60.0, +1, &y, commands));
  EXPECT_FALSE(s.fire(0, 70.0, +1, &y, commands));  // fires once
  ASSERT_EQ(commands.size(), 1u);
  EXPECT_EQ(commands[0].parameter, 5u);
  EXPECT_DOUBLE_EQ(commands[0].t_ms, 65.0);
  EXPECT_DOUBLE_EQ(s.p()[5], 65.0);
}

TEST(CommandSchedule, CrossingTimeSensitivityByImplicitFunction) {
  TwoSwitches m;
  solver::CommandSchedule s(m, m.parameters().values(), 500.0, {3, 4});
  // g = y - p[level]: d t / d tau = -s_y,tau / y', d t / d level = -(s_y,level - 1) / y'.
  const auto dte = s.crossing_time_sensitivity(0, 60.0, 0.5, {0.2, 0.1});
  ASSERT_EQ(dte.size(), 2u);
  EXPECT_DOUBLE_EQ(dte[0], -0.4);
  EXPECT_DOUBLE_EQ(dte[1], 1.8);
  EXPECT_THROW(s.crossing_time_sensitivity(0, 60.0, 0.0, {0.2, 0.1}), Error);  // tangential
}

TEST(CommandSchedule, CommandTimesBecomeStopsOrMergeWithOne) {
  TwoSwitches m;
  solver::CommandSchedule s(m, m.parameters().values(), 500.0, {3});
  using Added = solver::CommandSchedule::Added;
  EXPECT_EQ(s.add_command_time(100.0, {0.5}, 0), Added::Next);
  EXPECT_DOUBLE_EQ(s.next_stop(), 100.0);
  EXPECT_DOUBLE_EQ(s.next_stop_jump()[0], 0.5);
  EXPECT_EQ(s.add_command_time(200.0, {0.0}, 0), Added::Later);
  // Within 1e-9 of the stop at 120 (which moves by 1 with tau): the same switch, same jump.
  EXPECT_EQ(s.add_command_time(120.0 + 1e-10, {1.0}, 0), Added::Existing);
  // Moving differently from the switch it coincides with: no single jump.
  EXPECT_THROW(s.add_command_time(120.0, {3.0}, 0), Error);
  s.pass_stop();
  EXPECT_DOUBLE_EQ(s.next_stop(), 120.0);
  s.pass_stop();
  EXPECT_DOUBLE_EQ(s.next_stop(), 200.0);
}

TEST(CommandSchedule, JumpIsTheRightHandSideStepTimesTheSwitchTimeDerivative) {
  TwoSwitches m;
  solver::CommandSchedule s(m, m.parameters().values(), 500.0, {3, 0});
  // At tau = 120 the drive steps from a1 = 2 to a2 = 0.5: s += (2 - 0.5) d tau / dp.
  double s_tau = 0.25, s_a1 = 7.0;
  const double y = 30.0;
  s.apply_jump(120.0, {2.0, 0.0}, &y, {&s_tau, &s_a1});
  EXPECT_NEAR(s_tau, 0.25 + 1.5 * 2.0, 1e-12);
  EXPECT_EQ(s_a1, 7.0);
}

TEST(CvodesSession, DecayMatchesTheClosedFormAcrossARestart) {
  solver::SolverOptions so;
  so.rtol = so.atol = 1e-10;
  const double k = 0.02;
  auto rhs = [](sunrealtype, N_Vector y, N_Vector ydot, void* ud) {
    NV_Ith_S(ydot, 0) = -*static_cast<const double*>(ud) * NV_Ith_S(y, 0);
    return 0;
  };
  double k_data = k;
  solver::SundialsContext ctx;
  const double y0 = 3.0;
  solver::CvodesSession session(ctx.get(), so, &y0, 1, rhs, &k_data);
  session.set_linear_solver(solver::LinearSystem::Dense, 0, 0, nullptr);
  double t = 0.0;
  const long steps_before = test::advance_to_stop_at_50(session, &t);
  session.restart(t);
  EXPECT_EQ(session.total_steps(), steps_before);  // counted over the restart
  session.set_stop_time(100.0);
  EXPECT_GE(session.advance(100.0, &t, CV_NORMAL), 0);  // CV_SUCCESS or CV_TSTOP_RETURN: tout is the stop
  EXPECT_DOUBLE_EQ(t, 100.0);
  EXPECT_NEAR(NV_Ith_S(session.y(), 0), 3.0 * std::exp(-k * 100.0), 1e-8);
  EXPECT_GT(session.total_steps(), steps_before);
  EXPECT_EQ(session.stats().steps, session.total_steps());
}

TEST(CvodesSession, FailingSetupThrowsNamingTheCall) {
  solver::SolverOptions so;
  so.rtol = -1.0;  // CVodeSStolerances refuses it
  auto rhs = [](sunrealtype, N_Vector, N_Vector, void*) { return 0; };
  solver::SundialsContext ctx;
  const double y0 = 1.0;
  try {
    solver::CvodesSession session(ctx.get(), so, &y0, 1, rhs, nullptr);
    FAIL() << "no error";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("CVodeSStolerances"), std::string::npos) << e.what();
  }
  EXPECT_EQ(solver::cvodes_flag_name(CV_TOO_MUCH_WORK), "CV_TOO_MUCH_WORK");
}
