// Solver: jump conditions at parameter-dependent switch times against a closed form:
// y' = a(t) - k y with a = a1 before the command time tau and a2 after, y(0) = y0.
//   y(t) = a2/k + (y_tau - a2/k) exp(-k (t - tau)),  y_tau = a1/k + (y0 - a1/k) exp(-k tau)
//   dy(t)/dtau = (a1 - a2) exp(-k (t - tau)),  dy(t)/dy0 = exp(-k t)   (t > tau)
#include <gtest/gtest.h>

#include <cmath>

#include "solver/simulator.hpp"

using namespace phasmid;

namespace {

class CommandStep : public model::OdeModelT<CommandStep> {
 public:
  CommandStep() {
    params_.add({"cmd.a1", 2.0, "1/ms", "test", "drive before the command"});
    params_.add({"cmd.a2", 0.5, "1/ms", "test", "drive after the command"});
    params_.add({"cmd.k", 0.01, "1/ms", "test", "decay rate"});
    params_.add({"cmd.tau", 120.0, "ms", "test", "command time"});
    params_.add({"cmd.y0", 30.0, "1", "test", "initial value"});
    add_state("cmd.y", "1");
  }
  std::string kind() const override { return "command_step"; }
  std::vector<double> initial_state(const std::vector<double>& p) const override { return {p[4]}; }
  std::vector<double> breakpoints(const std::vector<double>& p, double) const override { return {p[3]}; }
  template <class T>
  void eval(double t, const T* y, const T* p, T* ydot) const {
    const T& a = t < model::value_of(p[3]) ? p[0] : p[1];
    ydot[0] = a - p[2] * y[0];
  }
};

}  // namespace

TEST(SegmentedSensitivity, CommandTimeAndInitialValueMatchClosedForm) {
  CommandStep m;
  auto p = m.parameters().values();
  const double a1 = p[0], a2 = p[1], k = p[2], tau = p[3], y0 = p[4];
  solver::SolverOptions so;
  so.rtol = so.atol = 1e-11;
  auto r = solver::Simulator(m, so).run(p, solver::output_grid(400, 25), {}, {0, 1, 2, 3, 4});
  ASSERT_EQ(r.t.size(), 17u);
  for (size_t i = 0; i < r.t.size(); ++i) {
    const double t = r.t[i];
    if (t == tau) continue;
    const double ytau = a1 / k + (y0 - a1 / k) * std::exp(-k * tau);
    double y, dy_da1, dy_da2, dy_dtau, dy_dy0;
    if (t < tau) {
      const double e = std::exp(-k * t);
      y = a1 / k + (y0 - a1 / k) * e;
      dy_da1 = (1 - e) / k;
      dy_da2 = 0;
      dy_dtau = 0;
      dy_dy0 = e;
    } else {
      const double e = std::exp(-k * (t - tau));
      y = a2 / k + (ytau - a2 / k) * e;
      dy_da1 = (1 - std::exp(-k * tau)) / k * e;
      dy_da2 = (1 - e) / k;
      dy_dtau = (a1 - a2) * e;
      dy_dy0 = std::exp(-k * t);
    }
    EXPECT_NEAR(r.state(i, 0), y, 1e-7 * std::abs(y)) << t;
    EXPECT_NEAR(r.sens(i, 0, 0), dy_da1, 1e-6 * std::abs(dy_da1) + 1e-9) << t;
    EXPECT_NEAR(r.sens(i, 0, 1), dy_da2, 1e-6 * std::abs(dy_da2) + 1e-9) << t;
    EXPECT_NEAR(r.sens(i, 0, 3), dy_dtau, 1e-6 * std::abs(dy_dtau) + 1e-9) << t;
    EXPECT_NEAR(r.sens(i, 0, 4), dy_dy0, 1e-6 * std::abs(dy_dy0)) << t;
  }
  // Without the jump the command-time sensitivity would stay 0; with it: (a1 - a2) exp(-2.8).
  auto alone = solver::Simulator(m, so).run(p, solver::output_grid(400, 25), {}, {3});
  EXPECT_NEAR(alone.sens(alone.t.size() - 1, 0, 0), 1.5 * std::exp(-2.8), 1e-7);
}
