// The windowed partitioned run's record of a part's steps (solver/step_history.hpp): the cubic
// Hermite interpolant of each step's end values and derivatives reproduces a cubic exactly,
// converges at fourth order on exp(t) within the analytic bound h^4/384 max|y''''|, carries a
// step's start from the previous one, and forgets steps as a window and a roll-back require.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "solver/step_history.hpp"

using phasmid::solver::StepHistory;

namespace {

// Two states: a cubic and exp(t), with their derivatives.
void values(double t, double* y, double* f) {
  y[0] = 1.0 - 2.0 * t + 0.5 * t * t + 0.25 * t * t * t;
  f[0] = -2.0 + t + 0.75 * t * t;
  y[1] = std::exp(t);
  f[1] = std::exp(t);
}

// Steps of size h from 0 to 1, the first with its start values, the others continuing.
StepHistory record_uniform(double h) {
  StepHistory hist(2);
  double y0[2], f0[2], yn[2], fn[2];
  values(0.0, y0, f0);
  const int n = static_cast<int>(std::lround(1.0 / h));
  for (int k = 0; k < n; ++k) {
    const double t0 = k * h, tn = (k + 1) * h;
    values(tn, yn, fn);
    if (k == 0) hist.record(t0, tn, y0, f0, yn, fn);
    else hist.record(t0, tn, nullptr, nullptr, yn, fn);
  }
  return hist;
}

double max_exp_error(const StepHistory& hist) {
  const std::vector<size_t> index{0, 1};
  double worst = 0.0, row[2], y[2], f[2];
  for (int i = 0; i <= 1000; ++i) {
    const double t = i / 1000.0;
    EXPECT_TRUE(hist.at(t, index, row)) << t;
    values(t, y, f);
    worst = std::max(worst, std::abs(row[1] - y[1]));
  }
  return worst;
}

}  // namespace

TEST(StepHistory, ReproducesACubicAndConvergesAtFourthOrder) {
  const std::vector<size_t> index{0, 1};
  const StepHistory hist = record_uniform(0.125);
  double row[2], y[2], f[2];
  for (double t : {0.0, 0.03, 0.125, 0.4, 0.77, 1.0}) {
    ASSERT_TRUE(hist.at(t, index, row));
    values(t, y, f);
    EXPECT_NEAR(row[0], y[0], 1e-14) << t;
  }
  // Hermite cubic error <= h^4 / 384 max|y''''|, here max|y''''| = e on [0, 1].
  const double e1 = max_exp_error(record_uniform(0.125)), e2 = max_exp_error(record_uniform(0.0625));
  EXPECT_LE(e1, std::pow(0.125, 4) / 384.0 * std::exp(1.0));
  EXPECT_LE(e2, std::pow(0.0625, 4) / 384.0 * std::exp(1.0));
  EXPECT_GT(e1 / e2, 14.0);
  EXPECT_LT(e1 / e2, 18.0);
}

TEST(StepHistory, DropsStepsForWindowsAndRollBacks) {
  const std::vector<size_t> index{1, 0};  // own state i into row[index[i]]
  StepHistory hist = record_uniform(0.25);  // [0, .25], [.25, .5], [.5, .75], [.75, 1]
  double row[2], y[2], f[2];
  EXPECT_FALSE(hist.at(1.5, index, row));
  EXPECT_TRUE(hist.continues_at(1.0));
  EXPECT_FALSE(hist.continues_at(0.9));
  hist.drop_before(0.6);  // steps ending before 0.6 go
  EXPECT_FALSE(hist.at(0.4, index, row));
  ASSERT_TRUE(hist.at(0.6, index, row));
  values(0.6, y, f);
  EXPECT_NEAR(row[1], y[0], 1e-14);
  hist.drop_from(0.6);  // a roll-back to 0.6: the step [.75, 1] goes, [.5, .75] stays
  EXPECT_FALSE(hist.at(0.8, index, row));
  EXPECT_FALSE(hist.continues_at(0.6));
  // The restart at 0.6 records its own start values (here of another function: a jump).
  const double y0[2] = {5.0, 5.0}, f0[2] = {0.0, 0.0}, yn[2] = {5.0, 5.0}, fn[2] = {0.0, 0.0};
  hist.record(0.6, 0.9, y0, f0, yn, fn);
  ASSERT_TRUE(hist.at(0.8, index, row));
  EXPECT_EQ(row[0], 5.0);
  EXPECT_EQ(row[1], 5.0);
  hist.drop_before(10.0);  // never the last step
  EXPECT_TRUE(hist.at(0.9, index, row));
}
