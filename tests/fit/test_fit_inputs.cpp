// Data and parameter files: formats, and one-line errors naming file:line for malformed input.
#include <gtest/gtest.h>

#include <cmath>

#include "common/error.hpp"
#include "config/fit_section.hpp"
#include "fit/kinematic_data.hpp"
#include "fit/optimizer.hpp"
#include "fit/parameter_table.hpp"
#include "fit/start_points.hpp"
#include "fit_test_util.hpp"

using namespace phasmid;

namespace {
std::string error_of(const std::function<void()>& f) {
  const std::string m = fittest::error_message(f);
  if (m.empty()) ADD_FAILURE() << "no error thrown";
  EXPECT_EQ(m.find('\n'), std::string::npos) << "error spans several lines: " << m;
  return m;
}
#define EXPECT_ERROR(expr, substr) EXPECT_NE(error_of([&] { expr; }).find(substr), std::string::npos) << error_of([&] { expr; })
}  // namespace

TEST(KinematicCsv, ReadsTimeAndAngleColumnsWithMissingSamples) {
  auto d = fit::parse_kinematic_csv("# synthetic\ntime_ms,middle.fti,middle.ctr\n0,45,30\n5,46.5,\n10,48,31\n", "k.csv");
  ASSERT_EQ(d.time_ms.size(), 3u);
  EXPECT_EQ(d.channels, (std::vector<std::string>{"middle.fti", "middle.ctr"}));
  EXPECT_DOUBLE_EQ(d.angles_deg[0][1], 46.5);
  EXPECT_TRUE(std::isnan(d.angles_deg[1][1]));
  // Round trip through the writer.
  auto e = fit::parse_kinematic_csv(fit::format_kinematic_csv(d, "comment"), "rt.csv");
  EXPECT_EQ(e.time_ms, d.time_ms);
  EXPECT_DOUBLE_EQ(e.angles_deg[1][2], 31);
}

TEST(KinematicCsv, MalformedInputNamesFileAndLine) {
  EXPECT_ERROR(fit::parse_kinematic_csv("time_ms,middle.fti\n0,45\n5,46,7\n", "a.csv"), "a.csv:3");
  EXPECT_ERROR(fit::parse_kinematic_csv("time_ms,middle.fti\n0,45\n5,4x6\n", "b.csv"), "b.csv:3: '4x6'");
  EXPECT_ERROR(fit::parse_kinematic_csv("time_ms,middle.fti\n0,45\n0,46\n", "c.csv"), "c.csv:3: times must increase");
  EXPECT_ERROR(fit::parse_kinematic_csv("t,middle.fti\n0,45\n", "d.csv"), "d.csv:1: column 't'");
  EXPECT_ERROR(fit::parse_kinematic_csv("time_ms,middle.femur\n0,45\n", "e.csv"), "e.csv:1");
  EXPECT_ERROR(fit::parse_kinematic_csv("time_ms,middle.fti\n", "f.csv"), "f.csv: no data rows");
  EXPECT_ERROR(fit::parse_kinematic_csv("time_ms,middle.fti\n,45\n", "g.csv"), "g.csv:2: missing value in column 'time_ms'");
  EXPECT_ERROR(fit::read_kinematic_csv("/nonexistent/x.csv"), "/nonexistent/x.csv: cannot read");
}

TEST(AniposeCsv, MapsColumnsAndConvertsFramesToMilliseconds) {
  fit::AniposeOptions o;
  o.frame_rate_hz = 200;
  o.columns = {{"R2_FTi_flex", "middle.fti"}};
  auto d = fit::parse_anipose_csv("L1_CF_flex,R2_FTi_flex,fnum\n10,45,0\n11,47,1\n12,50,2\n", "ap.csv", o);
  EXPECT_EQ(d.channels, std::vector<std::string>{"middle.fti"});
  EXPECT_DOUBLE_EQ(d.time_ms[2], 10.0);
  EXPECT_DOUBLE_EQ(d.angles_deg[0][1], 47.0);
  o.columns = {{"R2_missing", "middle.fti"}};
  EXPECT_ERROR(fit::parse_anipose_csv("a,fnum\n1,0\n", "ap.csv", o), "ap.csv:1: mapped column 'R2_missing'");
  o.columns = {{"a", "middle.fti"}};
  EXPECT_ERROR(fit::parse_anipose_csv("a,b\n1,0\n", "ap.csv", o), "no fnum column");
  o.frame_rate_hz = 0;
  EXPECT_ERROR(fit::parse_anipose_csv("a,fnum\n1,0\n", "ap.csv", o), "frame_rate_hz");
}

TEST(PetabTable, ReadsScalesBoundsAndEstimateFlags) {
  auto ps = fit::parse_parameter_table(
      "parameterId\tparameterName\tparameterScale\tlowerBound\tupperBound\tnominalValue\testimate\n"
      "middle.fti.b_v\tviscosity\tlog10\t1\t100\t12.5\t1\n"
      "middle.fti.k_E.flexion\t\tlin\t100\t1000\t510\t0\n",
      "p.tsv");
  ASSERT_EQ(ps.size(), 2u);
  EXPECT_EQ(ps[0].scale, fit::Scale::Log10);
  EXPECT_TRUE(ps[0].estimate);
  EXPECT_FALSE(ps[1].estimate);
  EXPECT_NEAR(fit::from_scaled(fit::Scale::Log10, fit::to_scaled(fit::Scale::Log10, 12.5)), 12.5, 1e-12);
  EXPECT_NEAR(fit::dtheta_dx(fit::Scale::Log, std::log(3.0)), 3.0, 1e-12);
  EXPECT_NEAR(fit::dtheta_dx(fit::Scale::Log10, 1.0), 10 * std::log(10.0), 1e-12);
  auto rt = fit::parse_parameter_table(fit::format_parameter_table(ps), "rt.tsv");
  EXPECT_EQ(rt[1].nominal, 510);
}

TEST(PetabTable, MalformedInputNamesFileAndLine) {
  const std::string h = "parameterId\tparameterScale\tlowerBound\tupperBound\tnominalValue\testimate\n";
  EXPECT_ERROR(fit::parse_parameter_table(h + "a\tlin\t0\t1\t0.5\t1\nb\tlin\t0\t1\n", "p.tsv"), "p.tsv:3");
  EXPECT_ERROR(fit::parse_parameter_table(h + "a\tlog2\t0\t1\t0.5\t1\n", "p.tsv"), "p.tsv:2: parameterScale");
  EXPECT_ERROR(fit::parse_parameter_table(h + "a\tlog\t0\t1\t0.5\t1\n", "p.tsv"), "p.tsv:2: parameter 'a': parameterScale log needs lowerBound > 0");
  EXPECT_ERROR(fit::parse_parameter_table(h + "a\tlin\t0\t1\t2\t1\n", "p.tsv"), "p.tsv:2: parameter 'a': nominalValue");
  EXPECT_ERROR(fit::parse_parameter_table(h + "a\tlin\t0\t1\t0.5\tyes\n", "p.tsv"), "p.tsv:2: estimate must be 0 or 1");
  EXPECT_ERROR(fit::parse_parameter_table(h + "a\tlin\tlow\t1\t0.5\t1\n", "p.tsv"), "p.tsv:2: 'low' in column 'lowerBound'");
  EXPECT_ERROR(fit::parse_parameter_table(h + "a\tlin\t2\t1\t0.5\t1\n", "p.tsv"), "lowerBound exceeds upperBound");
  EXPECT_ERROR(fit::parse_parameter_table(h + "a\tlin\t0\t1\t0.5\t1\na\tlin\t0\t1\t0.5\t1\n", "p.tsv"), "p.tsv:3: parameter 'a' listed twice");
  EXPECT_ERROR(fit::parse_parameter_table("parameterId\tlowerBound\n", "p.tsv"), "p.tsv:1: parameter table lacks column 'parameterScale'");
}

TEST(ParameterPattern, StarsAndQuestionMarksMatchAsDocumented) {
  using fit::parameter_id_matches;
  EXPECT_TRUE(parameter_id_matches("switch.S?.at_400ms", "switch.SL.at_400ms"));
  EXPECT_FALSE(parameter_id_matches("switch.S?.at_400ms", "switch.S.at_400ms"));
  EXPECT_TRUE(parameter_id_matches("*.k_E.*", "middle.fti.k_E.flexion"));
  EXPECT_FALSE(parameter_id_matches("*.k_E.*", "middle.fti.k_F.flexion"));
  EXPECT_TRUE(parameter_id_matches("middle.*", "middle."));  // '*' matches the empty run
  EXPECT_TRUE(parameter_id_matches("a*b*c", "axxbyybzc"));   // the last 'b' and 'c' decide
  EXPECT_FALSE(parameter_id_matches("a*b*c", "axxcyyb"));  // no c after the last b
  EXPECT_TRUE(parameter_id_matches("**?", "x"));
  EXPECT_FALSE(parameter_id_matches("**?", ""));
  EXPECT_TRUE(parameter_id_matches("middle.fti.k_E", "middle.fti.k_E"));
  EXPECT_FALSE(parameter_id_matches("middle.fti.k_E", "middle.fti.k_E.flexion"));
  // Many stars against a long name that fails only at its end: a backtracking matcher takes
  // exponential time on this (the fuzzer found it, fuzz/regressions/config/timeout-e41ee0...).
  const std::string stars = "middle.fti" + std::string(40, '*') + ".b_v";
  EXPECT_FALSE(parameter_id_matches(stars, "middle.fti." + std::string(200, 'x') + ".b_w"));
  EXPECT_TRUE(parameter_id_matches(stars, "middle.fti." + std::string(200, 'x') + ".b_v"));
}

TEST(FitConfig, ParsesTargetsInlineParametersAndRejectsUnknownKeys) {
  auto cfg = config::parse_config(R"(
[model]
type = "mechanical_joint"
[fit]
optimizer = "nlopt:bobyqa"
multistart = 4
sampling = "sobol"
[[fit.switch]]
angle = "middle.fti"
time_ms = 250
angle_deg = 110
angle_tolerance_deg = 0.5
velocity_tolerance_deg_s = 10
[[fit.feature]]
name = "middle.fti.angle_max_deg"
value = 110
tolerance = 1
set = "other"
[fit.parameters]
"middle.fti.b_v" = { scale = "log10", lower = 5, upper = 50 }
middle.fti.k_E.flexion = { lower = 100, upper = 2000, nominal = 600 }
)",
                                  "inline.toml");
  auto m = config::build_model(cfg);
  auto spec = fit::load_fit_spec(cfg, *m);
  EXPECT_EQ(spec.optimizer.method, "nlopt:BOBYQA");
  EXPECT_EQ(spec.multistart.starts, 4u);
  EXPECT_EQ(spec.targets.switches.size(), 1u);
  EXPECT_EQ(spec.targets.features.size(), 0u);  // other target set
  ASSERT_EQ(spec.parameters.size(), 2u);
  EXPECT_DOUBLE_EQ(spec.parameters[0].nominal, 12.5);  // model value
  EXPECT_EQ(spec.parameters[1].id, "middle.fti.k_E.flexion");
  EXPECT_DOUBLE_EQ(spec.parameters[1].nominal, 600);
  fit::FitOverrides ov;
  ov.target_set = "other";
  ov.optimizer = "ceres";
  auto other = fit::load_fit_spec(cfg, *m, ov);
  EXPECT_EQ(other.targets.features.size(), 1u);
  EXPECT_EQ(other.optimizer.method, "ceres");
  ov.optimizer = "nlopt:NEWTON";
  EXPECT_ERROR(fit::load_fit_spec(cfg, *m, ov), "--optimizer: unknown optimizer 'nlopt:NEWTON' (expected one of ceres, nlopt:BOBYQA,");

  auto bad = config::parse_config("[model]\ntype = \"mechanical_joint\"\n[fit]\noptimiser = \"ceres\"\n", "bad.toml");
  auto mb = config::build_model(bad);
  EXPECT_ERROR(fit::load_fit_spec(bad, *mb), "bad.toml:4: unknown key 'optimiser' in [fit]");
}

TEST(StartPoints, DeterministicStratifiedAndInsideTheBox) {
  auto a = fit::latin_hypercube(10, 3, 7), b = fit::latin_hypercube(10, 3, 7), c = fit::latin_hypercube(10, 3, 8);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  for (size_t d = 0; d < 3; ++d) {
    std::vector<int> strata(10, 0);
    for (auto& p : a) strata[static_cast<int>(p[d] * 10)]++;
    for (int s : strata) EXPECT_EQ(s, 1);
  }
  // Sobol without shift: the first points of dimension 1 and 2 are the known 0.5, 0.75/0.25, ...
  auto s = fit::sobol(4, 2, 0);
  EXPECT_DOUBLE_EQ(s[0][0], 0.5);
  EXPECT_DOUBLE_EQ(s[0][1], 0.5);
  EXPECT_DOUBLE_EQ(s[1][0], 0.75);
  EXPECT_DOUBLE_EQ(s[1][1], 0.25);
  EXPECT_DOUBLE_EQ(s[2][0], 0.25);
  EXPECT_DOUBLE_EQ(s[2][1], 0.75);
  // 2^k points of a Sobol sequence are stratified in each dimension.
  auto s16 = fit::sobol(16, 5, 3);
  for (size_t d = 0; d < 5; ++d) {
    std::vector<int> strata(16, 0);
    for (auto& p : s16) strata[static_cast<int>(p[d] * 16)]++;
    int empty = 0;
    for (int k : strata) empty += k == 0;
    EXPECT_LE(empty, 1) << "dimension " << d;  // point 0 is skipped
  }
}

TEST(FitConfig, EveryExampleFitConfigBuildsItsProblem) {
  for (const char* c : {"configs/fit_fti_section31.toml", "configs/fit_single_joint_gapp.toml",
                        "configs/fit_fti_kinematic_synthetic.toml", "configs/fit_fti_anipose_synthetic.toml",
                        "configs/fit_tripod_drives.toml"}) {
    SCOPED_TRACE(c);
    auto cfg = config::load_config(fittest::source(c));
    auto m = config::build_model(cfg);
    auto spec = fit::load_fit_spec(cfg, *m);
    fit::FitProblem p(*m, spec.parameters, spec.targets, spec.problem);
    EXPECT_GT(p.num_parameters(), 0u);
    EXPECT_GE(p.num_residuals(), p.num_parameters() - 1);
  }
  // The tripod drives are tied across the three legs.
  auto cfg = config::load_config(fittest::source("configs/fit_tripod_drives.toml"));
  auto m = config::build_model(cfg);
  auto spec = fit::load_fit_spec(cfg, *m);
  fit::FitProblem p(*m, spec.parameters, spec.targets, spec.problem);
  EXPECT_EQ(p.tied_parameters(0).size(), 3u);
  // Its per-leg step-period target has event-time gradients: any optimiser applies.
  EXPECT_TRUE(p.has_jacobian());
  // A gait-class target (a class, no gradient) leaves derivative-free optimisers only.
  fit::FeatureTarget gait = spec.targets.features[0];
  gait.feature = "gait_class";
  gait.value = 2;
  spec.targets.features.push_back(gait);
  fit::FitProblem q(*m, spec.parameters, spec.targets, spec.problem);
  EXPECT_FALSE(q.has_jacobian());
  EXPECT_NE(q.no_jacobian_reason().find("gait_class"), std::string::npos);
  fit::OptimizerOptions ceres, bobyqa;
  fit::parse_optimizer("ceres", ceres);
  fit::parse_optimizer("nlopt:BOBYQA", bobyqa);
  EXPECT_THROW(fit::check_optimizer(q, ceres), Error);
  EXPECT_NO_THROW(fit::check_optimizer(q, bobyqa));
  EXPECT_NO_THROW(fit::check_optimizer(p, ceres));
  // Targets come from the feature catalogue: a feature the model never computes (the first
  // channel has no phase lag; front -> middle is not one of the leg pairs) is an error at its
  // config line that lists the features with gradients and, apart, the class.
  for (const char* never : {"front.thc.phase_lag", "phase_lag.front_to_middle", "L2.step_period_ms"}) {
    fit::Targets t = spec.targets;
    t.features[0].feature = never;
    try {
      fit::FitProblem r(*m, spec.parameters, t, spec.problem);
      ADD_FAILURE() << never << " accepted";
    } catch (const Error& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(t.features[0].origin + ": unknown feature '" + never + "'", 0), 0u) << msg;
      EXPECT_NE(msg.find("phase_lag.hind_to_middle"), std::string::npos) << msg;
      EXPECT_NE(msg.find("values only, for derivative-free optimisers: gait_class, is_tetrapod, is_tripod, oscillates)"), std::string::npos) << msg;
    }
  }
}

// A parameter vector whose run leaves the joint's admissible range (docs/model.md "Admissible
// ranges") is a failed evaluation with the reason, not a residual: b_v = 0.01 g/s lets the
// Section 3.1 mechanics swing far beyond +-180 deg, while the start (Table A.14) evaluates.
TEST(FitEvaluation, ARunBeyondTheJointRangeIsAFailedEvaluation) {
  auto f = fittest::load_shipped_fit("configs/fit_fti_section31.toml");
  auto params = fittest::fti_parameters(*f.model, 0.01 / 12.5, 5.0);  // b_v down to 0.01 g/s
  fit::FitProblem p(*f.model, params, f.spec.targets, f.spec.problem);
  std::vector<double> x = p.start(), r(p.num_residuals());
  std::string error;
  ASSERT_TRUE(p.evaluate(x.data(), r.data(), nullptr, &error)) << error;
  ASSERT_EQ(p.estimated()[4].id, "middle.fti.b_v");
  x[4] = fit::to_scaled(fit::Scale::Log10, 0.01);
  EXPECT_FALSE(p.evaluate(x.data(), r.data(), nullptr, &error));
  EXPECT_NE(error.find("joint middle.fti left its admissible range [-180, 180] deg"), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}
