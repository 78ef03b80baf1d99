// Solver: sensitivities through an event-triggered command time against a closed form.
// y' = a(t) - k y, y(0) = 0, a = a1 before the command time tau and a2 after; a trigger sets
// tau = t_e + D, t_e the time y rises through the level L:
//   t_e = -ln(1 - k L / a1) / k,  y_tau = a1/k (1 - exp(-k tau)),
//   y(t) = a2/k + (y_tau - a2/k) exp(-k (t - tau))   (t > tau).
// D = 0: the command switches at the event itself (jump applied there); D = 50 ms: a breakpoint
// added at the event, the jump at tau with d tau / dp found at the event. The derivatives of the
// closed form are central differences of it (an exact function: error ~1e-9 relative).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "solver/simulator.hpp"
#include "../rising_trigger.hpp"

using namespace phasmid;

namespace {

class TriggeredStep : public model::OdeModelT<TriggeredStep> {
 public:
  explicit TriggeredStep(double delay_ms) {
    params_.add({"cmd.a1", 2.0, "1/ms", "test", "drive before the command"});
    params_.add({"cmd.a2", 0.5, "1/ms", "test", "drive after the command"});
    params_.add({"cmd.k", 0.01, "1/ms", "test", "decay rate"});
    params_.add({"cmd.tau", model::kUnresolvedMs, "ms", "test", "command time (triggered)"});
    params_.add({"cmd.level", 80.0, "1", "test", "trigger level"});
    add_state("cmd.y", "1");
    set_triggers({test::rising_trigger("cmd.y rises through cmd.level", 3, 0, 4, delay_ms)});
  }
  std::string kind() const override { return "triggered_step"; }
  std::vector<double> initial_state(const std::vector<double>&) const override { return {0.0}; }
  std::vector<double> breakpoints(const std::vector<double>& p, double) const override { return {p[3]}; }
  template <class T>
  void eval(double t, const T* y, const T* p, T* ydot) const {
    const T& a = t < model::value_of(p[3]) ? p[0] : p[1];
    ydot[0] = a - p[2] * y[0];
  }
};

// y(t) for t > tau, parameters (a1, a2, k, level).
double closed_form(double t, double D, const std::vector<double>& q) {
  const double a1 = q[0], a2 = q[1], k = q[2], L = q[3];
  const double tau = -std::log(1 - k * L / a1) / k + D;
  const double ytau = a1 / k * (1 - std::exp(-k * tau));
  return a2 / k + (ytau - a2 / k) * std::exp(-k * (t - tau));
}

void check(double D) {
  TriggeredStep m(D);
  auto p = m.parameters().values();
  solver::SolverOptions so;
  so.rtol = so.atol = 1e-11;
  const std::vector<size_t> sens = {0, 1, 2, 4};
  auto r = solver::Simulator(m, so).run(p, solver::output_grid(400, 25), {}, sens);
  ASSERT_EQ(r.commands.size(), 1u);
  const std::vector<double> q = {p[0], p[1], p[2], p[4]};
  const double t_e = -std::log(1 - p[2] * p[4] / p[0]) / p[2];
  EXPECT_NEAR(r.commands[0].t_ms, t_e + D, 1e-7);
  size_t checked = 0;
  double jump_part = 0;  // max over t of |d y / d level|: zero without the d tau / dp terms (level only moves tau)
  for (size_t i = 0; i < r.t.size(); ++i) {
    const double t = r.t[i];
    if (t <= t_e + D + 1) continue;
    EXPECT_NEAR(r.state(i, 0), closed_form(t, D, q), 1e-7 * std::abs(closed_form(t, D, q))) << t;
    for (size_t j = 0; j < q.size(); ++j) {
      const double h = 1e-5 * std::abs(q[j]);
      auto qp = q, qm = q;
      qp[j] += h;
      qm[j] -= h;
      const double exact = (closed_form(t, D, qp) - closed_form(t, D, qm)) / (2 * h);
      EXPECT_NEAR(r.sens(i, 0, j), exact, 1e-6 * std::abs(exact) + 1e-8) << "t " << t << " parameter " << j;
      if (j == 3) jump_part = std::max(jump_part, std::abs(exact));
    }
    ++checked;
  }
  EXPECT_GE(checked, 5u);
  EXPECT_GT(jump_part, 0.5);  // (a1 - a2) / (a1 - k L) exp(-k (t - tau)): 0.98 at the first output after tau
}

}  // namespace

TEST(TriggerJumps, CommandAtTheEventMatchesClosedForm) { check(0.0); }
TEST(TriggerJumps, CommandAfterTheEventMatchesClosedForm) { check(50.0); }
