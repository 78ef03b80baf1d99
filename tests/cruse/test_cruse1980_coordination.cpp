// Cruse (1980): the statements of the paper the model must reproduce.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cruse/cruse1980_features.hpp"
#include "cruse/cruse1980_model.hpp"
#include "cruse/cruse1980_sweep.hpp"

using namespace phasmid::cruse;

// Sect. 3: "the model showed a stable pattern for each walking speed independent of the
// particular starting position" with L1-R2 and L2-R3 protracting together (Sect. 2).
class AllStartPositions : public ::testing::TestWithParam<std::tuple<double, Stepping>> {};

TEST_P(AllStartPositions, SettleIntoOnePatternWithL1R2AndL2R3InPhase) {
  const auto [period, stepping] = GetParam();
  Parameters p = at_period(Parameters{}, period);
  p.stepping = stepping;
  Features first;
  for (int start = 1; start <= 10; ++start) {
    p.set("start_position", start);
    const Features f = measure(simulate(p), p);
    ASSERT_TRUE(f.locked) << "start position " << start;
    EXPECT_TRUE(in_phase(f, "L1-R2")) << "start position " << start;
    EXPECT_TRUE(in_phase(f, "L2-R3")) << "start position " << start;
    if (start == 1) first = f;
    else EXPECT_TRUE(same_pattern(first, f, 20.0)) << "start position " << start;
  }
}

INSTANTIATE_TEST_SUITE_P(GaitII, AllStartPositions,
                         ::testing::Combine(::testing::Values(400.0, 700.0, 1000.0, 1500.0, 2000.0),
                                            ::testing::Values(Stepping::Raster, Stepping::Continuous)));

// OL1 is the pacemaker: period = T0(OL1)/v_ret + T0(OL1)/v_pro = 10/(10/900) + 10/0.1 = 1000 ms.
TEST(Cruse1980, PeriodIsSetByOL1) {
  Parameters p;
  p.stepping = Stepping::Continuous;
  const Features f = measure(simulate(p), p);
  EXPECT_NEAR(f.period_ms, 1000.0, 1e-6);
}

// Hand computation for the event-exact model at P = 1000 ms: OL2 starts protracting when OL1
// has protracted (100 ms) and retracted to SL = 6.67 (6.67 * 90 ms = 600.3 ms), i.e. 700.3 ms
// after OL1; OL3 another 700.3 ms later (1400.6 ms = 400.6 ms into OL1's next period).
// Graham's lag L3 -> L1 = 1000 - 400.6 = 599.4 ms.
TEST(Cruse1980, GaitIILagMatchesHandComputation) {
  Parameters p;
  p.stepping = Stepping::Continuous;
  const Features f = measure(simulate(p), p);
  EXPECT_NEAR(f.lag_L3_L1_ms, 599.4, 1e-6);
  EXPECT_NEAR(f.phase[L2], 0.7003, 1e-6);
  EXPECT_NEAR(f.phase[L3], 0.4006, 1e-6);
}

// Sect. 3: in gait I the lags "lie on a straight line with the slope 1" against the period.
// The tripod makes L3 and L1 protract together, so Graham's "immediately following" L1 onset
// comes one period later: within one 20 ms raster step of the period (raster), exactly the
// period (event-exact).
class GaitI : public ::testing::TestWithParam<Stepping> {};

TEST_P(GaitI, LagGrowsWithPeriodWithSlopeOneFromAllStartPositions) {
  Parameters base;
  base.gait = Gait::I;
  base.stepping = GetParam();
  for (const char* s : {"SL", "SR", "SL1R1"}) base.set(std::string("gait1.switch.") + s, 5.0 / 3.0);
  const double allowed = GetParam() == Stepping::Raster ? 20.0 + 1e-9 : 1e-6;
  std::vector<double> periods{300, 500, 700, 1000, 1500, 2000}, lags;
  for (double period : periods) {
    Parameters p = at_period(base, period);
    for (int start = 1; start <= 10; ++start) {
      p.set("start_position", start);
      const Features f = measure(simulate(p), p);
      ASSERT_TRUE(f.locked) << period << " ms, start " << start;
      EXPECT_TRUE(in_phase(f, "L1-L3") && in_phase(f, "L1-R2") && in_phase(f, "L2-R3")) << period;
      EXPECT_LE(std::abs(f.lag_L3_L1_ms - period), allowed) << period << " ms, start " << start;
      if (start == 1) lags.push_back(f.lag_L3_L1_ms);
    }
  }
  // Least-squares slope of lag against period.
  double mp = 0, ml = 0;
  for (std::size_t i = 0; i < periods.size(); ++i) mp += periods[i] / periods.size(), ml += lags[i] / periods.size();
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < periods.size(); ++i) {
    sxy += (periods[i] - mp) * (lags[i] - ml);
    sxx += (periods[i] - mp) * (periods[i] - mp);
  }
  EXPECT_NEAR(sxy / sxx, 1.0, GetParam() == Stepping::Raster ? 0.01 : 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Tripod, GaitI, ::testing::Values(Stepping::Raster, Stepping::Continuous));

// Table 1: the listed values give a stable pattern; T0 of every other oscillator must stay
// above T0(OL1) = 10 ("the value T0 of the oscillator OL1 must be the lowest one of all").
TEST(Cruse1980, Table1ValuesAreStableAndT0BelowOL1IsNot) {
  const std::vector<double> periods{400, 700, 1000, 1500, 2000};
  const Parameters base;  // Table 1: T0 min 10.2 (OL2, OL3, OR1), 10.3 (OR2, OR3)
  EXPECT_TRUE(is_stable(base, periods));
  for (double t1 : {5.0, 6.0, 7.0, 8.0, 9.0}) {
    Parameters p = base;
    p.set("T1", t1);
    EXPECT_TRUE(is_stable(p, periods)) << "T1 = " << t1;
  }
  for (double t2 : {1.0, 2.0, 4.0, 6.0, 8.0, 9.0}) {
    Parameters p = base;
    p.set("T2", t2);
    EXPECT_TRUE(is_stable(p, periods)) << "T2 = " << t2;
  }
  for (const char* leg : {"L2", "L3", "R1", "R2", "R3"}) {
    Parameters p = base;
    p.set(std::string("T0.") + leg, 9.95);
    EXPECT_FALSE(is_stable(p, periods)) << "T0." << leg << " = 9.95";
  }
}

// The sweep itself: the T1 range found brackets Table 1's 5-9 to within one grid step
// (0.25): phasmid finds 4.5-9.25. T0 minima: every oscillator needs T0 > T0(OL1) = 10.
TEST(Cruse1980, SweepFindsTable1Ranges) {
  const Parameters base;
  const std::vector<double> periods{400, 500, 700, 1000, 1500, 2000};
  std::vector<double> t1_grid;
  for (double v = 3.0; v <= 10.5; v += 0.25) t1_grid.push_back(v);
  const auto t1 = sweep_axis(base, "T1", t1_grid, periods);
  EXPECT_TRUE(t1.contiguous);
  EXPECT_LE(t1.stable_min, 5.0);
  EXPECT_GE(t1.stable_min, 4.5);
  EXPECT_GE(t1.stable_max, 9.0);
  EXPECT_LE(t1.stable_max, 9.25);
  const auto t0 = sweep_axis(base, "T0.R2", {9.9, 9.95, 10.0, 10.05, 10.1, 10.2, 10.3, 10.4}, periods);
  EXPECT_TRUE(t0.contiguous);
  EXPECT_GT(t0.stable_min, 10.0);
  EXPECT_LE(t0.stable_min, 10.3);
}
