// Fits to recordings compared as step cycles (fit/targets.hpp StepCycleTarget,
// docs/recordings.md): the residual Jacobian of the phase profiles, period and duty factor
// from forward sensitivities and event-time derivatives against central finite differences,
// shown converging; and the refusals of a malformed target.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "config/config.hpp"
#include "fit/condition_problem.hpp"
#include "fit/fit_problem.hpp"
#include "fit/optimizer.hpp"
#include "fit_test_util.hpp"

using namespace phasmid;

namespace {

// The middle leg with rate motoneurons (smooth in its parameters), 5 model steps analysed.
struct LegSetup {
  config::Config cfg = config::parse_config(
      "[model]\ntype = \"leg\"\nleg = \"middle\"\nthc_table = \"A.17\"\nmotoneuron = \"rate\"\n"
      "[simulation]\nt_end_ms = 4200\ndiscard_ms = 1500\n",
      "leg.toml");
  std::unique_ptr<model::OdeModel> model = config::build_model(cfg);
  fit::ProblemSettings settings;
  LegSetup() {
    settings.solver = config::simulation_settings(cfg).solver;
    settings.solver.rtol = 1e-10;
    settings.solver.atol = 1e-10;
    settings.t_end_ms = 4200;
    settings.discard_ms = 1500;
  }
};

// A recording's summary with 20 bins; the Jacobian does not depend on its values.
fit::StepCycleTarget target() {
  fit::StepCycleTarget t;
  t.leg = "L2";
  t.model_leg = "middle";
  t.origin = "test";
  t.sample_ms = 0.25;
  features::StepCycles& d = t.data;
  d.channels = {"L2.thc", "L2.ctr", "L2.fti"};
  for (int k = 0; k < 20; ++k) d.phase.push_back((k + 0.5) / 20);
  d.mean_deg.assign(3, std::vector<double>(20, 0.0));
  d.sd_deg.assign(3, std::vector<double>(20, 2.0));
  d.median_period_ms = d.mean_period_ms = 800, d.period_sd_ms = 40, d.duty_factor = 0.7, d.duty_factor_sd = 0.03;
  d.steps.assign(3, features::Step{0, 500, 800, ""});
  const char* joints[] = {"thc", "ctr", "fti"};
  for (int j = 0; j < 3; ++j) {
    fit::Observable o;
    o.data_channel = std::string("L2.") + joints[j];
    o.model_channel = std::string("middle.") + joints[j];
    o.sign = j == 2 ? -1 : 1;
    o.origin = "test";
    if (j == 0) o.offset_parameter = "thc_offset";
    else o.offset_deg = 10;
    if (j == 2) o.scale_parameter = "fti_scale", o.sigma_parameter = "fti_sigma";
    t.observables.push_back(o);
  }
  return t;
}

std::vector<fit::FitParameter> parameters() {
  return {{"middle.thc.cpg.epsilon", fit::Scale::Log10, 0.001, 0.004, 0.0019, true, "test"},
          {"middle.ctr.cpg_lev.g_app", fit::Scale::Lin, 0.2, 0.5, 0.34, true, "test"},
          {"middle.fti.cpg_ext.g_app", fit::Scale::Lin, 0.1, 0.4, 0.209, true, "test"},
          {"thc_offset", fit::Scale::Lin, -100, 100, -70, true, "test"},
          {"fti_scale", fit::Scale::Lin, 0.5, 1.5, 0.8, true, "test"},
          {"fti_sigma", fit::Scale::Log, 0.5, 20, 2.0, true, "test"}};
}

// Max over residuals of |J - J_fd(h)| / max|column of J_fd(h)| for estimated parameter j.
double worst_error(const std::vector<double>& J, const std::vector<double>& Jfd, size_t m, size_t n, size_t j) {
  double scale = 0, worst = 0;
  for (size_t q = 0; q < m; ++q) scale = std::max(scale, std::abs(Jfd[q * n + j]));
  for (size_t q = 0; q < m; ++q) worst = std::max(worst, std::abs(J[q * n + j] - Jfd[q * n + j]) / scale);
  return worst;
}

}  // namespace

TEST(FitRecording, StepCycleJacobianMatchesConvergedFiniteDifferences) {
  LegSetup s;
  fit::Targets t;
  t.step_cycles.push_back(target());
  fit::FitProblem p(*s.model, parameters(), t, s.settings);
  ASSERT_EQ(p.num_residuals(), 3u * 20 + 2 + 2);  // bins, the FTi noise's two, period, duty factor
  const size_t m = p.num_residuals(), n = p.num_parameters();
  const std::vector<double> x = p.start();
  std::vector<double> r(m), J(m * n), J1(m * n), J2(m * n);
  std::string err;
  ASSERT_TRUE(p.evaluate(x.data(), r.data(), J.data(), &err)) << err;
  ASSERT_TRUE(p.jacobian_fd(x.data(), J1.data(), 1e-5, &err)) << err;
  ASSERT_TRUE(p.jacobian_fd(x.data(), J2.data(), 3e-6, &err)) << err;
  // As for the per-leg features (tests/sensitivity/test_leg_feature_sensitivity.cpp): an entry
  // is compared where the differences have converged (two steps agree to 0.25 %); it must then
  // agree to 1 %. Entries at the steep edges of the rate motoneurons' f-V relation do not
  // converge at these steps and are counted, not compared; they must be few. The profiles
  // interpolate outputs linearly, so a difference whose step moves a bin's time across an
  // output sees the interpolant's kink: the outputs are 0.25 ms apart here (the Jacobian is
  // that of the interpolant; at 1 ms, three of 120 entries differ by 1-3 % for this reason).
  size_t entries = 0, compared = 0;
  for (size_t j = 0; j < n; ++j) {
    double scale = 0;
    for (size_t q = 0; q < m; ++q) scale = std::max(scale, std::abs(J1[q * n + j]));
    ASSERT_GT(scale, 0.0) << p.estimated()[j].id;
    for (size_t q = 0; q < m; ++q) {
      const double a = J[q * n + j], b = J1[q * n + j], b2 = J2[q * n + j];
      if (std::abs(b) < 1e-4 * scale) continue;
      ++entries;
      if (std::abs(b - b2) > 0.0025 * std::abs(b)) continue;
      ++compared;
      EXPECT_NEAR(a, b, 0.01 * std::abs(b)) << p.estimated()[j].id << " at " << p.residual_labels()[q];
    }
  }
  EXPECT_GE(compared, entries * 8 / 10) << compared << " of " << entries << " entries converged";
  EXPECT_GE(compared, 100u);
  // The offset enters every bin of its observable with weight 1/sigma and nothing else; the
  // scale, sign * model / sigma (r = (sign scale model + offset - data) / sigma). The noise
  // (x = ln sigma) enters its bins as -r and its two residuals e1 = sqrt(n) (t + 1) and
  // e2 = sqrt(n) sqrt(M^2 - t^2), t = ln(sigma / sigma0), sigma0 = sqrt(0.5 * 20),
  // M = 0.75 ln(20 / 0.5), as sqrt(n) and -sqrt(n) t / sqrt(M^2 - t^2).
  const double sn = std::sqrt(20.0), t0 = std::log(2 / std::sqrt(10.0)), M = 0.75 * std::log(40.0);
  EXPECT_EQ(p.residual_labels()[60], "steps L2.fti noise");
  EXPECT_EQ(p.residual_labels()[61], "steps L2.fti noise bound");
  EXPECT_NEAR(r[60], sn * (t0 + 1), 1e-12);
  EXPECT_NEAR(r[61], sn * std::sqrt(M * M - t0 * t0), 1e-12);
  for (size_t q = 0; q < m; ++q) {
    EXPECT_DOUBLE_EQ(J[q * n + 3], q < 20 ? 0.5 : 0.0) << p.residual_labels()[q];
    if (q >= 40 && q < 60) EXPECT_NEAR(J[q * n + 4], -((10.0 - 2.0 * r[q]) / 0.8) / 2.0, 1e-9) << p.residual_labels()[q];
    else EXPECT_EQ(J[q * n + 4], 0.0) << p.residual_labels()[q];
    if (q >= 40 && q < 60) EXPECT_NEAR(J[q * n + 5], -r[q], 1e-12) << p.residual_labels()[q];
    else if (q == 60) EXPECT_NEAR(J[q * n + 5], sn, 1e-12);
    else if (q == 61) EXPECT_NEAR(J[q * n + 5], -sn * t0 / std::sqrt(M * M - t0 * t0), 1e-12);
    else EXPECT_EQ(J[q * n + 5], 0.0) << p.residual_labels()[q];
  }
}

// An estimated noise maximises the likelihood: with everything else fixed, sigma^2 is the mean
// squared difference of model and data over the observable's bins (closed form).
TEST(FitRecording, EstimatedNoiseIsTheRootMeanSquareDifference) {
  LegSetup s;
  auto params = parameters();
  for (auto& q : params) q.estimate = q.id == "fti_sigma";
  // The model's FTi profile through the observable (sigma 2 at the start, data 0), then data
  // that differ from it by known amounts d_k: sigma-hat = sqrt(mean d_k^2).
  fit::Targets t;
  t.step_cycles.push_back(target());
  std::vector<double> model(20), x, r;
  {
    fit::FitProblem p0(*s.model, params, t, s.settings);
    x = p0.start(), r.resize(p0.num_residuals());
    std::string err;
    ASSERT_TRUE(p0.evaluate(x.data(), r.data(), nullptr, &err)) << err;
    for (size_t k = 0; k < 20; ++k) model[k] = 2.0 * r[40 + k];
  }
  auto& d = t.step_cycles.back().data;
  double ss = 0;
  for (size_t k = 0; k < 20; ++k) {
    const double diff = 1 + 3 * std::sin(2 * M_PI * d.phase[k]);
    d.mean_deg[2][k] = model[k] - diff;
    ss += diff * diff;
  }
  const double expected = std::sqrt(ss / 20);  // 2.35, inside the bounds [0.5, 20]
  fit::FitProblem p(*s.model, params, t, s.settings);
  ASSERT_EQ(p.num_parameters(), 1u);
  // The cost's gradient J^T r in sigma vanishes there: -sum r_k^2 + n = 0 (exactly).
  const size_t m = p.num_residuals();
  std::vector<double> xs = {std::log(expected)}, rs(m), J(m);
  std::string err;
  ASSERT_TRUE(p.evaluate(xs.data(), rs.data(), J.data(), &err)) << err;
  double g = 0, g_start = 0;
  for (size_t q = 0; q < m; ++q) g += J[q] * rs[q];
  ASSERT_TRUE(p.evaluate(x.data(), r.data(), J.data(), &err)) << err;
  for (size_t q = 0; q < m; ++q) g_start += J[q] * r[q];
  EXPECT_NEAR(g, 0.0, 1e-12 * std::abs(g_start));
  // And the optimiser finds it (Gauss-Newton's curvature in sigma is close to the likelihood's
  // there, so a few iterations suffice).
  fit::OptimizerOptions o;
  o.function_tolerance = o.parameter_tolerance = o.gradient_tolerance = 1e-15;
  const fit::FitSummary f = fit::optimize(p, x, o);
  ASSERT_TRUE(f.usable) << f.message;
  std::printf("sigma %.10g expected %.10g, %d iterations: %s\n", std::exp(f.x[0]), expected, f.iterations, f.message.c_str());
  // The cost C (about 800 here, most of it the other observables' fixed residuals) resolves
  // ln(sigma) only to about sqrt(2 eps C / 2n), its curvature in ln(sigma) being 2n.
  const double resolution = std::sqrt(2 * 2.2e-16 * f.final_cost / 40);
  EXPECT_NEAR(std::log(std::exp(f.x[0]) / expected), 0.0, 3 * resolution) << "resolution " << resolution;
  EXPECT_GT(std::abs(std::exp(f.x[0]) - 2.0), 0.3);  // it moved from the start
  EXPECT_LE(f.iterations, 6);
}

TEST(FitRecording, RefusesWhatItCannotCompare) {
  LegSetup s;
  auto message = [&](const std::function<void(fit::StepCycleTarget&)>& edit) {
    fit::Targets t;
    t.step_cycles.push_back(target());
    edit(t.step_cycles.back());
    return fittest::error_message([&] { fit::FitProblem p(*s.model, parameters(), t, s.settings); });
  };
  EXPECT_EQ(message([](auto& t) { t.model_leg = "hind"; }), "test: the model has no ground contact for leg 'hind'");
  EXPECT_EQ(message([](auto& t) { t.observables[1].model_channel = "middle.femur"; }),
            "test: the model has no angle 'middle.femur' (it has: middle.thc, middle.ctr, middle.fti)");
  EXPECT_EQ(message([](auto& t) { t.observables[1].data_channel = "L2.tar"; }),
            "test: the recording has no channel 'L2.tar' (it has: L2.thc, L2.ctr, L2.fti)");
  EXPECT_EQ(message([](auto& t) { t.observables[1].sign = 2; }), "test: sign must be 1 or -1");
  EXPECT_EQ(message([](auto& t) { t.observables[2].offset_parameter = "nope"; }),
            "test: offset parameter 'nope' is not in the parameter table");
  EXPECT_EQ(message([](auto& t) { t.observables[1].scale_parameter = "thc_offset"; }),
            "test: parameter 'thc_offset' has two roles (deg and 1)");
  EXPECT_EQ(message([](auto& t) { t.observables[1].offset_parameter = "fti_sigma"; }),
            "test: parameter 'fti_sigma' has two roles (offset and noise)");
  EXPECT_EQ(message([](auto& t) { t.observables[2].sigma_parameter = "middle.fti.cpg.epsilon"; }),
            "test: noise parameter 'middle.fti.cpg.epsilon' is also a model parameter");
  EXPECT_EQ(message([](auto& t) { t.data.period_sd_ms = std::nan(""); }),
            "test: the recording's period and duty factor have no step-to-step SD (3 step kept); give period_sigma_ms and "
            "duty_factor_sigma");
}

// Two trials (PEtab conditions) of one model: the FTi extensor drive is each trial's own, the
// rest shared, and trial b fixes the levator drive. The stacked problem's residuals and
// Jacobian are those of the two trials' own problems, built by hand, placed in their rows and
// columns.
TEST(FitRecording, ConditionsStackTheirTrialsAndShareTheRest) {
  LegSetup s;
  std::vector<fit::FitParameter> all;
  for (const auto& q : parameters())
    if (q.id != "middle.fti.cpg_ext.g_app") all.push_back(q);
  all.push_back({"gapp_a", fit::Scale::Lin, 0.1, 0.4, 0.209, true, "test"});
  all.push_back({"gapp_b", fit::Scale::Lin, 0.1, 0.4, 0.25, true, "test"});
  fit::Targets t;
  t.step_cycles = {target(), target()};
  t.step_cycles[0].condition = "a";
  t.step_cycles[1].condition = "b";
  t.step_cycles[1].data.mean_deg[1].assign(20, 5.0);
  fit::Condition a{"a", {{"middle.fti.cpg_ext.g_app", "gapp_a"}}, {}, "a.toml:1"};
  fit::Condition b{"b", {{"middle.fti.cpg_ext.g_app", "gapp_b"}}, {{"middle.ctr.cpg_lev.g_app", 0.3}}, "b.toml:1"};
  fit::ConditionsProblem p(*s.model, all, t, s.settings, {a, b});
  ASSERT_EQ(p.num_conditions(), 2u);
  // Global estimates: eps, ctr lev, thc_offset, fti_scale, fti_sigma, gapp_a, gapp_b.
  ASSERT_EQ(p.num_parameters(), 7u);
  auto part = [&](const std::string& gapp, double gapp_start, bool fixed_lev) {
    std::vector<fit::FitParameter> ps;
    for (const auto& q : parameters())
      if (q.id != "middle.fti.cpg_ext.g_app" && !(fixed_lev && q.id == "middle.ctr.cpg_lev.g_app")) ps.push_back(q);
    ps.push_back({"middle.fti.cpg_ext.g_app", fit::Scale::Lin, 0.1, 0.4, gapp_start, true, gapp});
    if (fixed_lev) ps.push_back({"middle.ctr.cpg_lev.g_app", fit::Scale::Lin, 0.3, 0.3, 0.3, false, "b"});
    return ps;
  };
  fit::Targets ta, tb;
  ta.step_cycles = {t.step_cycles[0]};
  tb.step_cycles = {t.step_cycles[1]};
  fit::FitProblem pa(*s.model, part("gapp_a", 0.209, false), ta, s.settings);
  fit::FitProblem pb(*s.model, part("gapp_b", 0.25, true), tb, s.settings);
  const size_t ma = pa.num_residuals(), mb = pb.num_residuals(), m = p.num_residuals(), n = 7;
  ASSERT_EQ(m, ma + mb);
  EXPECT_EQ(p.residual_labels()[0], "[a] " + pa.residual_labels()[0]);
  EXPECT_EQ(p.residual_labels()[ma], "[b] " + pb.residual_labels()[0]);
  const std::vector<double> x = p.start();
  std::vector<double> r(m), J(m * n), ra(ma), Ja(ma * 6), rb(mb), Jb(mb * 5);
  std::string err;
  ASSERT_TRUE(p.evaluate(x.data(), r.data(), J.data(), &err)) << err;
  // Part a's estimates: eps, lev, thc_offset, fti_scale, fti_sigma, gapp_a -> global 0-5;
  // part b's: eps, thc_offset, fti_scale, fti_sigma, gapp_b -> global 0, 2, 3, 4, 6.
  const std::vector<size_t> ca = {0, 1, 2, 3, 4, 5}, cb = {0, 2, 3, 4, 6};
  std::vector<double> xa, xb;
  for (size_t j : ca) xa.push_back(x[j]);
  for (size_t j : cb) xb.push_back(x[j]);
  ASSERT_TRUE(pa.evaluate(xa.data(), ra.data(), Ja.data(), &err)) << err;
  ASSERT_TRUE(pb.evaluate(xb.data(), rb.data(), Jb.data(), &err)) << err;
  for (size_t q = 0; q < m; ++q) {
    const bool in_a = q < ma;
    EXPECT_EQ(r[q], in_a ? ra[q] : rb[q - ma]) << p.residual_labels()[q];
    for (size_t j = 0; j < n; ++j) {
      const auto& cols = in_a ? ca : cb;
      const auto k = std::find(cols.begin(), cols.end(), j);
      const double want = k == cols.end() ? 0.0
                          : in_a          ? Ja[q * 6 + static_cast<size_t>(k - cols.begin())]
                                          : Jb[(q - ma) * 5 + static_cast<size_t>(k - cols.begin())];
      EXPECT_EQ(J[q * n + j], want) << p.residual_labels()[q] << ", " << p.estimated()[j].id;
    }
  }
  EXPECT_NE(r[ma + 20], ra[20]);  // the trials differ (b's CTr data, its fixed levator drive)
  EXPECT_EQ(p.tied_parameters(5), std::vector<std::string>{"middle.fti.cpg_ext.g_app"});
  EXPECT_EQ(p.parameter_unit(6), "nS");
}

TEST(FitRecording, ConditionsRefuseWhatTheyCannotMap) {
  LegSetup s;
  auto message = [&](std::vector<fit::Condition> cs, const std::function<void(fit::Targets&, std::vector<fit::FitParameter>&)>& edit) {
    std::vector<fit::FitParameter> all = parameters();
    all.push_back({"gapp_a", fit::Scale::Lin, 0.1, 0.4, 0.209, true, "test"});
    fit::Targets t;
    t.step_cycles = {target()};
    t.step_cycles[0].condition = "a";
    edit(t, all);
    return fittest::error_message([&] { fit::ConditionsProblem p(*s.model, all, t, s.settings, cs); });
  };
  const fit::Condition a{"a", {{"middle.fti.cpg_ext.g_app", "gapp_a"}}, {}, "c.toml:3"};
  auto none = [](fit::Targets&, std::vector<fit::FitParameter>&) {};
  EXPECT_EQ(message({}, none), "test: condition 'a' is not defined (give [fit.conditions.a])");
  EXPECT_EQ(message({a, {"b", {}, {{"middle.ctr.cpg_lev.g_app", 0.3}}, "c.toml:5"}}, none),
            "c.toml:5: condition 'b' has no targets (give a [[fit.recording]] condition = \"b\")");
  EXPECT_EQ(message({{"a", {{"middle.fti.cpg_ext.g_app", "nope"}}, {}, "c.toml:3"}}, none),
            "c.toml:3: condition 'a' sets 'middle.fti.cpg_ext.g_app' to 'nope', which is not in [fit.parameters]");
  EXPECT_EQ(message({{"a", {{"middle.fti.cpg_ext.g_app", "middle.ctr.cpg_lev.g_app"}}, {}, "c.toml:3"}}, none),
            "c.toml:3: condition 'a' sets 'middle.fti.cpg_ext.g_app' to 'middle.ctr.cpg_lev.g_app', a model parameter; give "
            "the condition's parameter a name of its own");
  // The shared middle.fti.cpg_ext.g_app is set by the one condition: it would estimate nothing.
  EXPECT_EQ(message({a}, none),
            "test: parameter 'middle.fti.cpg_ext.g_app' is estimated but no condition uses it (every condition sets it, or no "
            "target names it)");
  EXPECT_EQ(message({{"a", {{"middle.fti.cpg_ext.g_app", "gapp_a"}}, {{"middle.fti.nope", 1.0}}, "c.toml:3"}},
                    [](fit::Targets&, std::vector<fit::FitParameter>& ps) { ps.erase(ps.begin() + 2); }),
            "condition 'a': c.toml:3: unknown parameter 'middle.fti.nope'; `phasmid params CONFIG` lists them");
}
