// Every NLopt algorithm offered runs on a two-parameter FTi kinematic fit and returns a usable
// summary (local ones at the optimum Ceres finds, global ones within their budget), and the
// Ceres robust loss resists outliers that bias plain least squares.
#include <gtest/gtest.h>

#include "fit/optimizer.hpp"
#include "fit_test_util.hpp"

using namespace phasmid;

namespace {
struct Two {
  config::Config cfg = config::load_config(fittest::source("configs/fti_mechanical.toml"));
  std::unique_ptr<model::OdeModel> model = config::build_model(cfg);
  std::unique_ptr<fit::FitProblem> problem;
  explicit Two(bool outliers = false) {
    fit::Targets t;
    fit::KinematicTarget k;
    k.data = fittest::synthetic_fti({{"middle.fti.b_v", 15.0}, {"middle.fti.k_E.flexion", 600.0}}, 1000.0, 10.0, 0.5, 21);
    if (outliers)
      for (size_t s = 3; s < k.data.time_ms.size(); s += 10) k.data.angles_deg[0][s] += 25.0;  // 10 % gross errors
    k.sigma_deg = 0.5;
    t.kinematics.push_back(k);
    fit::ProblemSettings s;
    s.solver = config::simulation_settings(cfg).solver;
    s.solver.rtol = s.solver.atol = 1e-6;
    auto ps = fittest::fti_parameters(*model, 0.5, 2.0);
    for (size_t j = 1; j < 4; ++j) ps[j].estimate = false;
    problem = std::make_unique<fit::FitProblem>(*model, ps, t, s);
  }
};
}  // namespace

TEST(Backends, EveryNloptAlgorithmRunsAndLocalOnesFindTheOptimum) {
  Two f;
  fit::OptimizerOptions co;
  auto ref = fit::optimize(*f.problem, f.problem->start(), co);
  ASSERT_TRUE(ref.converged);
  for (const fit::OptimizerInfo& a : fit::optimizers()) {
    if (a.backend != fit::Backend::NLopt) continue;
    SCOPED_TRACE(a.name);
    fit::OptimizerOptions o;
    fit::parse_optimizer(a.name, o);
    const bool global = a.global;
    o.max_evaluations = global ? 500 : 1000;
    o.function_tolerance = 1e-10;
    o.parameter_tolerance = 1e-8;
    auto s = fit::optimize(*f.problem, f.problem->start(), o);
    ASSERT_TRUE(s.usable) << s.message;
    EXPECT_LT(s.final_cost, s.initial_cost);
    if (!global) {
      EXPECT_TRUE(s.converged) << s.termination;
      EXPECT_NEAR(s.final_cost, ref.final_cost, 1e-3 * ref.final_cost);
    } else {
      // Within 500 evaluations the excess cost over the optimum shrinks by at least 90 %.
      EXPECT_LT(s.final_cost - ref.final_cost, 0.1 * (s.initial_cost - ref.final_cost));
    }
  }
}

TEST(Backends, HuberLossResistsOutliers) {
  Two f(true);
  fit::OptimizerOptions plain, huber;
  huber.loss = "huber";
  huber.loss_scale = 3.0;  // residuals beyond 3 sigma count linearly
  auto a = fit::optimize(*f.problem, f.problem->start(), plain);
  auto b = fit::optimize(*f.problem, f.problem->start(), huber);
  ASSERT_TRUE(a.usable && b.usable);
  auto ea = f.problem->to_linear(a.x), eb = f.problem->to_linear(b.x);
  const double err_plain = std::abs(ea[1] / 15.0 - 1), err_huber = std::abs(eb[1] / 15.0 - 1);
  EXPECT_LT(err_huber, 0.03);
  EXPECT_LT(err_huber, err_plain);
  EXPECT_NEAR(eb[0] / 600.0, 1.0, 0.03);
}

TEST(Backends, FailingSimulationsGiveASummaryNotACrash) {
  // A model the integrator cannot handle (an absurd tendon geometry): the fit finishes with
  // the solver's reason in its summary.
  auto cfg = config::load_config(fittest::source("configs/fti_mechanical.toml"));
  auto m = config::build_model(cfg, {"middle.fti.l_E0=0.1"});  // the CLI test's CVODES failure
  fit::Targets t;
  fit::KinematicTarget k;
  k.data = fittest::synthetic_fti({}, 500.0, 10.0, 0.5, 1);
  t.kinematics.push_back(k);
  fit::ProblemSettings s;
  fit::FitProblem p(*m, fittest::fti_parameters(*m), t, s);
  fit::OptimizerOptions o;
  auto r = fit::optimize(p, p.start(), o);
  EXPECT_FALSE(r.converged);
  EXPECT_FALSE(r.usable);
  EXPECT_NE(r.message.find("CVODES"), std::string::npos) << r.message;
  fit::parse_optimizer("nlopt:BOBYQA", o);
  o.max_evaluations = 20;
  auto r2 = fit::optimize(p, p.start(), o);
  EXPECT_FALSE(r2.usable);
  EXPECT_NE(r2.message.find("CVODES"), std::string::npos) << r2.message;
}
