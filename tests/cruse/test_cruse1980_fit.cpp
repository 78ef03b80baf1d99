// `phasmid fit` on the Cruse (1980) model: the Fig. 3 switch nodes fitted to the statements of
// the text (configs/fit_cruse1980_switch.toml, docs/cruse1980.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.hpp"
#include "config/config.hpp"
#include "config/fit_section.hpp"
#include "cruse/cruse1980_fit.hpp"
#include "cruse/cruse1980_sweep.hpp"
#include "fit/fit_run.hpp"
#include "build_info.hpp"

using namespace phasmid;
using namespace phasmid::cruse;

namespace {

const std::string kConfig = std::string(PHASMID_SOURCE_DIR) + "/configs/fit_cruse1980_switch.toml";

struct CruseFit {
  fit::FitSpec spec;
  std::unique_ptr<CruseFitProblem> problem;
};

// The fit as `phasmid fit` builds it: the config layer reads [fit], the cruse1980 scenario of
// the config makes its problem.
CruseFit load_fit(const fit::FitOverrides& ov = {}) {
  const config::Config cfg = config::load_config(kConfig);
  CruseFit cf;
  const auto scenario = config::build_scenario(cfg);
  cf.spec = config::fit_spec(cfg, *scenario, ov);
  auto problem = scenario->make_fit(cf.spec);
  cf.problem.reset(dynamic_cast<CruseFitProblem*>(problem.release()));
  if (!cf.problem) throw Error("not a cruse1980 fit problem");
  return cf;
}

// All ten Table 2 starting positions lock into one pattern with L1-R2 and L2-R3 in phase, and
// the left and right lags agree within one raster step.
void expect_text_statements(const Parameters& fitted, double period, Stepping stepping) {
  Parameters p = at_period(fitted, period);
  p.stepping = stepping;
  Features first;
  for (int start = 1; start <= 10; ++start) {
    p.set("start_position", start);
    const Features f = measure(simulate(p), p);
    const std::string where = "period " + std::to_string(period) + " ms, start " + std::to_string(start) +
                              (stepping == Stepping::Raster ? " (raster)" : " (continuous)");
    ASSERT_TRUE(f.locked) << where;
    EXPECT_TRUE(in_phase(f, "L1-R2")) << where;
    EXPECT_TRUE(in_phase(f, "L2-R3")) << where;
    EXPECT_LE(std::abs(f.lag_R3_R1_ms - f.lag_L3_L1_ms), 20.0) << where;
    if (start == 1) first = f;
    else EXPECT_TRUE(same_pattern(first, f, 20.0)) << where;
  }
}

// Runs the fit as `phasmid fit` does and checks that it converged and that every weighted
// residual is within its tolerance; returns the parameters at the optimum.
Parameters fit_and_check(CruseFit& cf) {
  cf.spec.optimizer.progress = false;
  const CruseFitProblem& problem = *cf.problem;
  const fit::FitResult result = fit::run_fit(problem, cf.spec);
  const fit::FitSummary& best = result.best();
  EXPECT_TRUE(best.usable);
  EXPECT_TRUE(best.converged) << best.termination << " " << best.message;
  std::vector<double> r(problem.num_residuals());
  EXPECT_TRUE(problem.evaluate(best.x.data(), r.data(), nullptr));
  for (size_t i = 0; i < r.size(); ++i) EXPECT_LE(std::abs(r[i]), 1.0) << problem.residual_labels()[i];
  return problem.parameters_at(best.x.data());
}

}  // namespace

// The shipped fit, run as `phasmid fit` runs it: from the neutral start (every node at 5) to
// nodes meeting every target, then checked at the node periods and between them, in the
// event-exact model the fit used and in Cruse's 20 ms raster.
TEST(Cruse1980Fit, FittedSwitchNodesMeetTheTextStatements) {
  CruseFit cf = load_fit();
  const CruseFitProblem& problem = *cf.problem;
  ASSERT_EQ(problem.num_parameters(), 12u);
  std::vector<double> r0(problem.num_residuals());
  ASSERT_TRUE(problem.evaluate(problem.start().data(), r0.data(), nullptr));
  double start_cost = 0;
  for (double v : r0) start_cost += 0.5 * v * v;
  EXPECT_GT(start_cost, 100.0) << "the neutral start should violate the statements";

  const Parameters fitted = fit_and_check(cf);
  // "As the speed increases the 'switch position' moves anteriorly": non-decreasing in the period.
  const auto& nodes = switch_node_periods();
  for (const std::string s : {"SL", "SR", "SL1R1"})
    for (size_t i = 1; i < nodes.size(); ++i) {
      const auto at = [&](size_t k) { return fitted.get("switch." + s + ".at_" + std::to_string(int(nodes[k])) + "ms"); };
      EXPECT_LE(at(i - 1), at(i) + 1e-9) << s << " between " << nodes[i - 1] << " and " << nodes[i] << " ms";
    }
  EXPECT_EQ(fitted.get("switch.SL.at_1000ms"), fitted.get("switch.SR.at_1000ms"));  // tied by "S?"

  for (double period : {400.0, 500.0, 600.0, 700.0, 800.0, 1000.0, 1200.0, 1500.0, 1800.0, 2000.0})
    for (Stepping s : {Stepping::Continuous, Stepping::Raster}) expect_text_statements(fitted, period, s);
}

// The statements fix SL1R1 given SL (left-right symmetry) but not the level of SL: the
// closed-form defaults of configs/cruse1980_gait2.toml, a different curve, meet every target as well.
TEST(Cruse1980Fit, TextStatementsDoNotFixTheSwitchLevel) {
  CruseFit cf = load_fit();
  const CruseFitProblem& problem = *cf.problem;
  std::vector<double> x;
  const Parameters defaults;
  for (size_t j = 0; j < problem.num_parameters(); ++j) x.push_back(defaults.get(problem.tied_parameters(j).front()));
  std::vector<double> r(problem.num_residuals());
  ASSERT_TRUE(problem.evaluate(x.data(), r.data(), nullptr));
  for (size_t i = 0; i < r.size(); ++i) EXPECT_LE(std::abs(r[i]), 1.0) << problem.residual_labels()[i];
}

// With a lag curve the nodes are determined: the target set closed_form_lag asks for Graham's
// lag L3 -> L1 = 2 Delta(P), Delta(P) = 100 ms + (P - 200 ms)/4, and the fit from the neutral
// start must land on the closed form of docs/cruse1980.md,
//   SL(P) = 10 (1 - Delta/(P - 100 ms)),  SL1R1(P) = 10 - SL(P) - 1000 ms/(P - 100 ms),
// within what the tolerances allow: lag +- 2 ms moves SL by 10 * 1 ms/(P - 100 ms); the
// left-right lag difference +- 20 ms moves SL1R1 by 10 * 20 ms/(P - 100 ms).
TEST(Cruse1980Fit, LagTargetsDetermineTheNodes) {
  fit::FitOverrides ov;
  ov.target_set = "closed_form_lag";
  CruseFit cf = load_fit(ov);
  const Parameters fitted = fit_and_check(cf);
  for (double P : switch_node_periods()) {
    const std::string at = ".at_" + std::to_string(int(P)) + "ms";
    const double delta = 100.0 + (P - 200.0) / 4.0;
    const double sl = 10.0 * (1.0 - delta / (P - 100.0));
    EXPECT_NEAR(fitted.get("switch.SL" + at), sl, 10.0 * 1.0 / (P - 100.0)) << P;
    EXPECT_NEAR(fitted.get("switch.SL1R1" + at), 10.0 - sl - 1000.0 / (P - 100.0), 10.0 * 20.0 / (P - 100.0)) << P;
  }
}

TEST(Cruse1980Fit, OptimisersThatNeedJacobiansAreRejectedInOneLine) {
  for (const std::string opt : {"ceres", "nlopt:LBFGS", "nlopt:SLSQP"}) {
    fit::FitOverrides ov;
    ov.optimizer = opt;
    try {
      load_fit(ov);
      FAIL() << opt << " accepted";
    } catch (const Error& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.find('\n'), std::string::npos) << m;
      EXPECT_NE(m.find("needs a gradient but the model has none"), std::string::npos) << m;
      EXPECT_NE(m.find("nlopt:BOBYQA"), std::string::npos) << m;
    }
  }
}

TEST(Cruse1980Fit, FeaturesComputedFromRuns) {
  // Event-exact hand computation at P = 1000 ms with the default nodes (SL = 6.67,
  // SL1R1 = 2.22): OL2 protracts 100 + 6.67 * 90 = 700.3 ms after OL1, OL3 another 700.3 ms
  // later (phase 0.4006); OR1 100 + 2.22 * 90 = 299.8 ms after OL1; OR2 with OL1; OR3 with OL2.
  Parameters p = at_period(Parameters{}, 1000.0);
  p.stepping = Stepping::Continuous;
  const Features f = measure(simulate(p), p);
  ASSERT_TRUE(f.locked);
  EXPECT_NEAR(run_feature("phase.L2", f, f), 0.7003, 1e-9);
  EXPECT_NEAR(run_feature("phase.L3", f, f), 0.4006, 1e-9);
  EXPECT_NEAR(run_feature("gap_ms.L1-R2", f, f), 0.0, 1e-6);
  EXPECT_NEAR(run_feature("gap_ms.L2-R3", f, f), 0.0, 1e-6);
  EXPECT_NEAR(run_feature("gap_ms.L1-L2", f, f), 299.7, 1e-6);  // circular: 1000 - 700.3
  EXPECT_NEAR(run_feature("lag_difference_ms", f, f), f.lag_R3_R1_ms - f.lag_L3_L1_ms, 0.0);
  EXPECT_EQ(run_feature("pattern_deviation_ms", f, f), 0.0);
  // Back to front: L3 -> L2 = 299.7 ms, L2 -> L1 = 299.7 ms, together less than a period.
  EXPECT_EQ(run_feature("wave_excess_ms", f, f), 0.0);
  EXPECT_EQ(run_feature("locked", f, f), 1.0);
}

TEST(Cruse1980Fit, SwitchReversalMeasuresPosteriorShiftsWithSpeed) {
  Parameters p;
  EXPECT_EQ(parameter_feature("switch_reversal.SL", p), 0.0);
  p.set("switch.SL.at_400ms", 6.5);  // above the 600 ms node (6.0) by 0.5
  p.set("switch.SL.at_1500ms", 6.5);  // below the 1000 ms node (6.67) by 0.17
  EXPECT_NEAR(parameter_feature("switch_reversal.SL", p), 0.5 + (6.67 - 6.5), 1e-12);
  EXPECT_EQ(parameter_feature("switch_reversal.SR", p), 0.0);
}
