// Issue 5 "done means": the tripod fit of configs/fit_tripod_drives.toml (the LD CPG drives of
// all three legs, tied, Section 3.3) reaches the tripod's step period of 442 ms and LD 1:1 from
// the tetrapod drives under tripod start conditions, and the legs then walk in a tripod.
// Expensive: each BOBYQA evaluation is a plain 3.8 s run of the 240-state three-leg network
// (~25 evaluations).
#include <gtest/gtest.h>

#include <cmath>

#include "features/features.hpp"
#include "config/fit_section.hpp"
#include "fit/fit_run.hpp"
#include "fit_test_util.hpp"

using namespace phasmid;

TEST(FitTripod, ReachesStepPeriod442AndOneToOneFromTheTetrapodDrives) {
  auto f = fittest::load_shipped_fit("configs/fit_tripod_drives.toml");
  auto& m = f.model;
  auto& spec = f.spec;
  fit::FitProblem& p = *f.problem;
  ASSERT_EQ(spec.targets.features[0].feature, "middle.step_period_ms");
  ASSERT_EQ(spec.targets.features[1].feature, "middle.ctr.levation_fraction");
  auto start = p.to_linear(p.start());
  ASSERT_NEAR(start[0], 0.34, 1e-12);  // tetrapod levator drive (docs/walking_model.md)
  ASSERT_NEAR(start[1], 0.14, 1e-12);  // tetrapod depressor drive
  std::vector<double> r(p.num_residuals());
  ASSERT_TRUE(p.evaluate(p.start().data(), r.data(), nullptr));
  EXPECT_GT(r[0], 40.0);  // the tetrapod drives step > 40 ms slower than 442 ms

  fit::FitSummary s = fit::optimize(p, p.start(), spec.optimizer);
  ASSERT_TRUE(s.usable) << s.message;
  ASSERT_TRUE(p.evaluate(s.x.data(), r.data(), nullptr));
  const double period = 442.0 + r[0] * spec.targets.features[0].tolerance;
  const double levation = 0.5 + r[1] * spec.targets.features[1].tolerance;
  EXPECT_NEAR(period, 442.0, 2.0);
  EXPECT_NEAR(levation, 0.5, 0.02);

  // The fitted drives walk in a tripod: front and hind in phase, middle in antiphase.
  auto best = p.simulate(s.x.data(), 5.0);
  features::FeatureOptions fo;
  fo.discard_ms = spec.problem.discard_ms;
  double gait = -1;
  for (auto& x : features::compute_features(*m, best, fo))
    if (x.name == "gait_class") gait = x.value;
  EXPECT_EQ(gait, 2.0) << "tripod";
}
