// Step cycles (features/step_cycles.hpp): a signal that is a known function of the step phase,
// sampled at 200 Hz over steps of different periods, each step shifted by its own offset. The
// summary must give back the function (to linear interpolation's error bound), the offsets'
// SD per bin, the median period and the duty factor exactly, and apply each documented rule.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "features/step_cycles.hpp"

using namespace phasmid;
using features::Stance;

namespace {

constexpr double kPi = 3.14159265358979323846;
double profile(double p) { return 110 - 30 * std::cos(2 * kPi * p) + 10 * std::sin(4 * kPi * p); }
// Linear interpolation's error bound: max|f''| h^2 / 8, h = one sample in phase units.
double interpolation_bound(double period_ms, double dt_ms) {
  const double h = dt_ms / period_ms;
  return (30 * 4 * kPi * kPi + 10 * 16 * kPi * kPi) * h * h / 8;
}

struct Synthetic {
  std::vector<double> t, x;
  std::vector<Stance> stances;
};

// Touchdowns at `td` (ms), lift-off after `duty` of each step, offsets per step.
Synthetic make(const std::vector<double>& td, double duty, const std::vector<double>& offset, double dt = 5) {
  Synthetic s;
  for (double t = 0; t <= td.back() + 1e-9; t += dt) {
    size_t i = 0;
    while (i + 2 < td.size() && t >= td[i + 1]) ++i;
    const double p = (t - td[i]) / (td[i + 1] - td[i]);
    s.t.push_back(t);
    s.x.push_back(profile(p) + offset[i]);
  }
  for (size_t i = 0; i < td.size(); ++i)
    s.stances.push_back({td[i], i + 1 < td.size() ? td[i] + duty * (td[i + 1] - td[i]) : std::nan("")});
  return s;
}

features::StepCycles summarise(const Synthetic& s, features::StepCycleOptions o = {}) {
  return features::step_cycles(s.t, {"L2.fti"}, {s.x}, s.stances, o, "test");
}

double sd(std::vector<double> v) {
  double m = 0, q = 0;
  for (double a : v) m += a / static_cast<double>(v.size());
  for (double a : v) q += (a - m) * (a - m);
  return std::sqrt(q / static_cast<double>(v.size() - 1));
}

}  // namespace

TEST(StepCycles, RecoversProfileOffsetsPeriodAndDutyFactor) {
  const std::vector<double> td = {100, 900, 1750, 2550, 3400, 4250, 5100};  // periods 800, 850, 800, 850, 850, 850
  const std::vector<double> off = {9, 1.5, -2, 0.5, 3, -1, 0};
  const Synthetic s = make(td, 0.7, off);
  const features::StepCycles c = summarise(s);
  ASSERT_EQ(c.steps.size(), 6u);
  EXPECT_EQ(c.steps[0].dropped, "start transient");
  EXPECT_EQ(c.kept(), 5u);
  EXPECT_DOUBLE_EQ(c.median_period_ms, 850);  // of 850, 800, 850, 850, 850
  EXPECT_NEAR(c.duty_factor, 0.7, 1e-12);
  EXPECT_NEAR(c.duty_factor_sd, 0, 1e-12);
  EXPECT_NEAR(c.period_sd_ms, sd({850, 800, 850, 850, 850}), 1e-9);
  EXPECT_NEAR(c.mean_period_ms, 840, 1e-9);
  const std::vector<double> kept_off(off.begin() + 1, off.begin() + 6);
  double mean_off = 0;
  for (double o : kept_off) mean_off += o / 5;
  const double bound = 2 * interpolation_bound(800, 5);
  ASSERT_EQ(c.phase.size(), 50u);
  for (size_t k = 0; k < c.phase.size(); ++k) {
    EXPECT_DOUBLE_EQ(c.phase[k], (k + 0.5) / 50);
    EXPECT_NEAR(c.mean_deg[0][k], profile(c.phase[k]) + mean_off, bound) << "bin " << k;
    EXPECT_NEAR(c.sd_deg[0][k], sd(kept_off), bound) << "bin " << k;
  }
}

TEST(StepCycles, DropsPeriodOutliersAndStepsWithMissingSamples) {
  // Step 3 lasts twice as long (a pause); step 5 has a missing sample.
  const std::vector<double> td = {0, 800, 1600, 3200, 4000, 4800, 5600, 6400};
  Synthetic s = make(td, 0.6, std::vector<double>(td.size(), 0));
  const size_t gap = static_cast<size_t>((4000 + 200) / 5);
  s.x[gap] = std::nan("");
  const features::StepCycles c = summarise(s);
  ASSERT_EQ(c.steps.size(), 7u);
  EXPECT_EQ(c.steps[0].dropped, "start transient");
  EXPECT_EQ(c.steps[1].dropped, "");
  EXPECT_EQ(c.steps[2].dropped, "period outlier: 1600 ms is more than 30 % from the median 800 ms");
  EXPECT_EQ(c.steps[4].dropped, "missing samples in L2.fti");
  EXPECT_EQ(c.kept(), 4u);
  EXPECT_DOUBLE_EQ(c.median_period_ms, 800);
  EXPECT_NEAR(c.duty_factor, 0.6, 1e-12);
  // With a wider tolerance the pause counts; with discard_steps = 0 the first step counts.
  features::StepCycleOptions o;
  o.max_period_deviation = 1.5;
  o.discard_steps = 0;
  EXPECT_EQ(summarise(s, o).kept(), 6u);
}

TEST(StepCycles, CensoredStancesAreNoSteps) {
  // A stance under way at the first sample (no touchdown) and one without its lift-off.
  Synthetic s = make({0, 800, 1600, 2400, 3200}, 0.5, std::vector<double>(5, 0));
  s.stances[0].touchdown_ms = std::nan("");
  s.stances[2].liftoff_ms = std::nan("");
  const features::StepCycles c = summarise(s);
  ASSERT_EQ(c.steps.size(), 3u);  // 800-1600, 1600-2400, 2400-3200
  EXPECT_EQ(c.steps[0].dropped, "start transient");
  EXPECT_EQ(c.steps[1].dropped, "no lift-off");
  EXPECT_EQ(c.kept(), 1u);
  EXPECT_TRUE(std::isnan(c.sd_deg[0][0]));  // one step: no spread
}

TEST(StepCycles, StancesFromAContactSignal) {
  const std::vector<double> t = {0, 5, 10, 15, 20, 25, 30, 35};
  const std::vector<Stance> s = features::stances_from_contact(t, {1, 1, 0, 0, 1, 1, 0, 1});
  ASSERT_EQ(s.size(), 3u);
  EXPECT_TRUE(std::isnan(s[0].touchdown_ms));  // in contact at the first sample: censored
  EXPECT_EQ(s[0].liftoff_ms, 7.5);  // halfway between the samples at 5 and 10 ms
  EXPECT_EQ(s[1].touchdown_ms, 17.5);
  EXPECT_EQ(s[1].liftoff_ms, 27.5);
  EXPECT_EQ(s[2].touchdown_ms, 32.5);
  EXPECT_TRUE(std::isnan(s[2].liftoff_ms));  // in contact at the last sample: censored
}

TEST(StepCycles, OneLineErrors) {
  const Synthetic s = make({0, 800, 1600}, 0.5, {0, 0, 0});
  auto message = [&](std::vector<Stance> st, features::StepCycleOptions o = {}) {
    try {
      features::step_cycles(s.t, {"L2.fti"}, {s.x}, st, o, "trial.mat: L2");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  std::vector<Stance> no_liftoff = s.stances;
  no_liftoff[1].liftoff_ms = std::nan("");
  EXPECT_EQ(message(no_liftoff),
            "trial.mat: L2: no step left of 2 touchdown-to-touchdown intervals: 1 start transient, 1 no lift-off (step rules: docs/recordings.md)");
  EXPECT_EQ(message({{0, 400}, {300, 700}}), "trial.mat: L2: stance 2 touches down (300 ms) before the previous stance ends (400 ms)");
  EXPECT_EQ(message({{500, 400}}), "trial.mat: L2: stance 1 lifts off (400 ms) before it touches down (500 ms)");
  features::StepCycleOptions o;
  o.bins = 1;
  EXPECT_EQ(message(s.stances, o), "trial.mat: L2: bins must be >= 2 (is 1)");
}
