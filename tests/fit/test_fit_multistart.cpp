// Multistart is deterministic for a given seed (same starts, same results, whatever the
// thread schedule), finds the optimum from spread-out starts, and profiles and standard errors
// behave: delta chi^2 is 0 at the optimum and grows away from it.
#include <gtest/gtest.h>

#include "fit/multistart.hpp"
#include "fit/uncertainty.hpp"
#include "fit_test_util.hpp"

using namespace phasmid;

namespace {
struct Kin {
  config::Config cfg = config::load_config(fittest::source("configs/fti_mechanical.toml"));
  std::unique_ptr<model::OdeModel> model = config::build_model(cfg);
  std::unique_ptr<fit::FitProblem> problem;
  Kin() {
    fit::Targets t;
    fit::KinematicTarget k;
    k.data = fittest::synthetic_fti({{"middle.fti.b_v", 15.0}, {"middle.fti.k_E.flexion", 600.0}}, 1000.0, 10.0, 0.5, 11);
    k.sigma_deg = 0.5;
    t.kinematics.push_back(k);
    fit::ProblemSettings s;
    s.solver = config::simulation_settings(cfg).solver;
    s.solver.rtol = s.solver.atol = 1e-6;
    auto ps = fittest::fti_parameters(*model, 0.5, 2.0);
    for (size_t j = 1; j < 4; ++j) ps[j].estimate = false;  // k_E.flexion and b_v only
    problem = std::make_unique<fit::FitProblem>(*model, ps, t, s);
  }
};
}  // namespace

TEST(Multistart, DeterministicForASeedAndAllStartsReachTheOptimum) {
  Kin k;
  fit::OptimizerOptions o;
  fit::MultistartOptions ms;
  ms.starts = 6;
  ms.seed = 99;
  ms.threads = 2;
  auto a = fit::multistart(*k.problem, o, ms);
  ms.threads = 1;
  auto b = fit::multistart(*k.problem, o, ms);
  ASSERT_EQ(a.runs.size(), 6u);
  for (size_t i = 0; i < a.runs.size(); ++i) {
    EXPECT_EQ(a.runs[i].x_start, b.runs[i].x_start);
    EXPECT_EQ(a.runs[i].x, b.runs[i].x);  // bitwise: each start's result depends only on its start
    EXPECT_TRUE(a.runs[i].converged) << "start " << i << ": " << a.runs[i].message;
    EXPECT_NEAR(a.runs[i].final_cost, a.runs[a.best].final_cost, 1e-6 * a.runs[a.best].final_cost);
  }
  EXPECT_EQ(a.runs[0].x_start, k.problem->start());  // start 0 is the nominal vector
  ms.sampling = fit::Sampling::Sobol;
  auto c = fit::multistart(*k.problem, o, ms);
  EXPECT_NE(c.runs[1].x_start, a.runs[1].x_start);
  auto est = k.problem->to_linear(a.runs[a.best].x);
  EXPECT_NEAR(est[0] / 600.0, 1.0, 0.03);
  EXPECT_NEAR(est[1] / 15.0, 1.0, 0.03);
}

TEST(Profile, DeltaChi2IsZeroAtTheOptimumAndCrossesTheThresholdNearTwoStandardErrors) {
  Kin k;
  fit::OptimizerOptions o;
  auto s = fit::optimize(*k.problem, k.problem->start(), o);
  ASSERT_TRUE(s.converged);
  auto u = fit::estimate_uncertainty(*k.problem, s.x, true);
  ASSERT_TRUE(u.ok) << u.message;
  auto pr = fit::profile_likelihood(*k.problem, s.x, s.final_cost, 1, u.sigma2, u.standard_error_scaled, 5, 2.0, o);
  ASSERT_EQ(pr.values.size(), 5u);
  EXPECT_NEAR(pr.delta_chi2[2], 0.0, 1e-6);
  // At +-2 SE a nearly quadratic profile gives delta chi^2 ~ 4 (3.84 = 95 %).
  EXPECT_NEAR(pr.delta_chi2[0], 4.0, 0.6);
  EXPECT_NEAR(pr.delta_chi2[4], 4.0, 0.6);
  EXPECT_GT(pr.delta_chi2[1], 0.5);
  EXPECT_LT(pr.delta_chi2[1], pr.delta_chi2[0]);
}
