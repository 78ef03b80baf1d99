// The samplers against posteriors known in closed form, the diagnostics against processes
// with known autocorrelation, and the priors against their normalisation (docs/sampling.md).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "common/error.hpp"
#include "fit/parameter_table.hpp"
#include "fit/residual_problem.hpp"
#include "sample/diagnostics.hpp"
#include "sample/evidence.hpp"
#include "sample/sample_run.hpp"
#include "sample/sampler.hpp"

namespace phasmid {
namespace {

// A user's problem in a few lines: residuals r(theta) of linear-scale parameters.
class FunctionProblem : public fit::ResidualProblem {
 public:
  using Residuals = std::function<std::vector<double>(const std::vector<double>& theta)>;
  FunctionProblem(std::vector<fit::FitParameter> p, size_t m, Residuals f) : f_(std::move(f)) {
    params_ = est_ = std::move(p);
    for (size_t i = 0; i < m; ++i) labels_.push_back("r" + std::to_string(i));
  }
  std::string parameter_unit(size_t) const override { return "1"; }
  std::vector<std::string> tied_parameters(size_t j) const override { return {est_[j].id}; }
  bool has_jacobian() const override { return false; }
  bool evaluate(const double* x, double* r, double* J, std::string*) const override {
    if (J) return false;
    const auto v = f_(to_linear(std::vector<double>(x, x + num_parameters())));
    std::copy(v.begin(), v.end(), r);
    return true;
  }
  void write_model_output(io::H5Writer&, const double*, bool, double) const override {}

 private:
  Residuals f_;
};

fit::FitParameter parameter(const std::string& id, double lo, double hi, fit::Prior prior = {}) {
  fit::FitParameter p;
  p.id = id, p.lower = lo, p.upper = hi, p.nominal = 0.5 * (lo + hi), p.prior = prior;
  return p;
}

sample::Chains chains_of(const sample::SamplerResult& r, size_t j, size_t from) {
  sample::Chains c(r.chains);
  for (size_t k = 0; k < r.chains; ++k)
    for (size_t i = from; i < r.draws; ++i) c[k].push_back(r.at(k, i, j));
  return c;
}

double mean_of(const sample::Chains& c) {
  double s = 0, n = 0;
  for (auto& ch : c)
    for (double v : ch) s += v, n += 1;
  return s / n;
}

// The integral of exp(log density) over the bounds, on the scaled axis (trapezoid, 20001 points).
double prior_mass(const fit::Prior& p, fit::Scale s, double lo, double hi) {
  const double a = fit::to_scaled(s, lo), b = fit::to_scaled(s, hi);
  const int n = 20000;
  double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const double x = a + (b - a) * i / n;
    sum += (i == 0 || i == n ? 0.5 : 1.0) * std::exp(fit::log_prior_density(p, s, lo, hi, x));
  }
  return sum * (b - a) / n;
}

TEST(Priors, EveryTypeIsANormalisedDensityOnEveryScale) {
  // Wide bounds hold all but a negligible tail, so each density must integrate to 1 over the
  // scaled axis: this checks the formulas and the Jacobian |d theta / d x| of priors on theta.
  struct Case {
    const char* type;
    const char* params;
    double lo, hi;
  };
  const Case cases[] = {{"uniform", "2;5", 1, 10},         {"normal", "5;0.5", 1, 10},
                        {"laplace", "5;0.3", 1, 10},       {"logNormal", "1.5;0.2", 1, 10},
                        {"logLaplace", "1.5;0.1", 1, 10},  {"parameterScaleNormal", "0.7;0.05", 1, 10},
                        {"parameterScaleLaplace", "0.7;0.03", 1, 10}, {"parameterScaleUniform", "0.2;0.8", 1, 10}};
  for (const Case& c : cases)
    for (fit::Scale s : {fit::Scale::Lin, fit::Scale::Log, fit::Scale::Log10}) {
      const fit::Prior p = fit::parse_prior(c.type, c.params, "t.tsv:2");
      // parameterScale* priors are stated on x: their parameters fit only the log10 axis here.
      const bool on_x = std::string(c.type).rfind("parameterScale", 0) == 0;
      if (on_x && s != fit::Scale::Log10) continue;
      EXPECT_NEAR(prior_mass(p, s, c.lo, c.hi), 1.0, 2e-4) << c.type << " on " << fit::scale_name(s);
    }
  // Undeclared: uniform on the scale within the bounds.
  EXPECT_NEAR(prior_mass(fit::Prior{}, fit::Scale::Log, 1, 10), 1.0, 1e-9);
  EXPECT_EQ(fit::log_prior_density(fit::Prior{}, fit::Scale::Lin, 1, 10, 11.0), -INFINITY);
  // Normal on theta at its mean, on the lin scale: -ln(sd sqrt(2 pi)).
  EXPECT_NEAR(fit::log_prior_density(fit::parse_prior("normal", "5;0.5", "x"), fit::Scale::Lin, 1, 10, 5.0),
              -std::log(0.5 * std::sqrt(2 * M_PI)), 1e-14);
}

TEST(Priors, MalformedDeclarationsNameTheirPlace) {
  auto msg = [](const char* t, const char* p) {
    try {
      fit::parse_prior(t, p, "p.tsv:3");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(msg("gauss", "0;1").rfind("p.tsv:3: objectivePriorType 'gauss' is not one of", 0), 0u);
  EXPECT_EQ(msg("normal", "0"), "p.tsv:3: objectivePriorParameters of normal must be two numbers 'a;b', got '0'");
  EXPECT_EQ(msg("normal", "0;-1"), "p.tsv:3: normal prior needs a positive second parameter (sd or scale), got '0;-1'");
  EXPECT_EQ(msg("uniform", "2;1"), "p.tsv:3: uniform prior needs lower < upper, got '2;1'");
  EXPECT_EQ(msg("normal", "0;x"), "p.tsv:3: objectivePriorParameters: 'x' is not a finite number");
  EXPECT_EQ(msg("", "0;1"), "p.tsv:3: objectivePriorParameters without objectivePriorType");
  // The parameter table reads and writes the two PEtab columns.
  const std::string t =
      "parameterId\tparameterScale\tlowerBound\tupperBound\tnominalValue\testimate\tobjectivePriorType\tobjectivePriorParameters\n"
      "a\tlog10\t1\t100\t10\t1\tlogNormal\t2;0.5\nb\tlin\t0\t1\t0.5\t1\t\t\n";
  const auto ps = fit::parse_parameter_table(t, "p.tsv");
  EXPECT_TRUE(ps[0].prior.declared);
  EXPECT_EQ(ps[0].prior.type, fit::PriorType::LogNormal);
  EXPECT_FALSE(ps[1].prior.declared);
  EXPECT_EQ(fit::format_parameter_table(ps), "parameterId\tparameterScale\tlowerBound\tupperBound\tnominalValue\testimate\tobjectivePriorType\tobjectivePriorParameters\n"
                                             "a\tlog10\t1\t100\t10\t1\tlogNormal\t2;0.5\nb\tlin\t0\t1\t0.5\t1\t\t\n");
}

TEST(Diagnostics, EffectiveSampleSizeOfAnAutoregressiveProcess) {
  // AR(1) x_t = rho x_t-1 + e_t: integrated autocorrelation time (1 + rho) / (1 - rho).
  const double rho = 0.9;
  const size_t n = 200000;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> e;
  sample::Chains c(2, std::vector<double>(n));
  for (auto& ch : c) {
    double x = e(rng) / std::sqrt(1 - rho * rho);  // stationary from the start
    for (double& v : ch) v = x = rho * x + e(rng);
  }
  const double expected = 2.0 * n * (1 - rho) / (1 + rho);
  // The estimator's relative error is about sqrt(2 (2M + 1) / N) for a window of M lags
  // (~100 here, Sokal 1997): 0.02; 4 of those.
  EXPECT_NEAR(sample::effective_sample_size(c) / expected, 1.0, 0.08);
  EXPECT_NEAR(sample::split_rhat(c), 1.0, 0.005);
  // Independent draws: ESS = n within the same error; white noise has M ~ 1.
  sample::Chains w(1, std::vector<double>(n));
  for (double& v : w[0]) v = e(rng);
  EXPECT_NEAR(sample::effective_sample_size(w) / n, 1.0, 0.03);
}

TEST(Diagnostics, SplitRhatAndBurnInSeeDriftingChains) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> e;
  const size_t n = 4000;
  // Two chains around different means: R-hat far above 1.01.
  sample::Chains shifted(2, std::vector<double>(n));
  for (size_t k = 0; k < 2; ++k)
    for (double& v : shifted[k]) v = e(rng) + (k ? 1.0 : 0.0);
  EXPECT_GT(sample::split_rhat(shifted), 1.1);
  // A transient decaying from 20 sd with time constant 100 draws: the burn-in rule cuts it
  // where it is still 2.7 sd (t = 200) and keeps the draws where it is below 0.01 sd
  // (t = 800); of stationary chains it drops only the first twentieth.
  sample::Chains drift(2, std::vector<double>(n)), flat(2, std::vector<double>(n));
  for (size_t k = 0; k < 2; ++k)
    for (size_t i = 0; i < n; ++i) {
      drift[k][i] = 20.0 * std::exp(-double(i) / 100.0) + e(rng);
      flat[k][i] = e(rng);
    }
  const size_t b = sample::burn_in({drift});
  EXPECT_GE(b, 400u);
  EXPECT_LE(b, 800u);
  // Stationary chains: the test at the first start (n/20) passes with probability 95 % by
  // construction; over 40 seeds more than 6 failures has probability 0.4 % (binomial).
  int later = 0;
  for (int seed = 100; seed < 140; ++seed) {
    std::mt19937_64 g(static_cast<std::uint64_t>(seed));
    for (auto& ch : flat)
      for (double& v : ch) v = e(g);
    const size_t fb = sample::burn_in({flat});
    EXPECT_GE(fb, n / 20);
    later += fb > n / 20;
  }
  EXPECT_LE(later, 6);
  EXPECT_NEAR(sample::normal_two_sided_quantile(0.05), 1.959963984540054, 1e-12);
  EXPECT_EQ(sample::diagnostic_warnings("k", 50, 1.2).size(), 2u);
  EXPECT_TRUE(sample::diagnostic_warnings("k", 500, 1.005).empty());
}

// y = A theta + noise (sd s = 0.5), two parameters with normal priors N(0, 2^2), five data.
struct LinearGaussian {
  Eigen::MatrixXd A = (Eigen::MatrixXd(5, 2) << 1, 0.5, 0.3, 1, -0.7, 0.2, 1.2, -0.4, 0.1, 0.9).finished();
  Eigen::VectorXd y = (Eigen::VectorXd(5) << 1.1, -0.3, 0.4, 2.0, 0.2).finished();
  double s = 0.5;
  fit::Prior prior = fit::parse_prior("normal", "0;2", "test");
  FunctionProblem problem{{parameter("a", -40, 40, prior), parameter("b", -40, 40, prior)}, 5,
                          [this](const std::vector<double>& t) {
                            const Eigen::VectorXd r = (A * Eigen::Vector2d(t[0], t[1]) - y) / s;
                            return std::vector<double>(r.data(), r.data() + r.size());
                          }};
  fit::FitSpec fs = [] {
    fit::FitSpec f;
    f.absolute_sigma = true;
    return f;
  }();
};

TEST(Sampling, LinearGaussianPosteriorMeanAndCovarianceInClosedForm) {
  // y = A theta + noise (sd 0.5), normal priors N(0, 2^2): the posterior is Gaussian with
  // covariance S = (A^T A / s^2 + I / 4)^-1 and mean S A^T y / s^2.
  LinearGaussian lg;
  const Eigen::MatrixXd& A = lg.A;
  const Eigen::VectorXd& y = lg.y;
  const double s = lg.s;
  const Eigen::MatrixXd S = (A.transpose() * A / (s * s) + Eigen::MatrixXd::Identity(2, 2) / 4.0).inverse();
  const Eigen::VectorXd mu = S * A.transpose() * y / (s * s);
  const FunctionProblem& problem = lg.problem;
  const fit::FitSpec& fs = lg.fs;
  sample::SampleSpec spec;
  spec.sampler.chains = 4, spec.sampler.draws = 20000, spec.sampler.seed = 11;
  const sample::SampleResult res = sample::run_sampling(problem, fs, spec);
  EXPECT_LT(res.burn_in, spec.sampler.draws / 4);
  const auto& r = res.run;
  std::vector<sample::Chains> c = {chains_of(r, 0, res.burn_in), chains_of(r, 1, res.burn_in)};
  double cov01 = 0, n = 0;
  const double m0 = mean_of(c[0]), m1 = mean_of(c[1]);
  for (size_t k = 0; k < r.chains; ++k)
    for (size_t i = 0; i < c[0][k].size(); ++i) cov01 += (c[0][k][i] - m0) * (c[1][k][i] - m1), n += 1;
  cov01 /= n - 1;
  for (int j = 0; j < 2; ++j) {
    const auto& p = res.parameters[static_cast<size_t>(j)];
    const double sd = std::sqrt(S(j, j));
    // Monte Carlo standard errors from the effective sample size: of the mean sd/sqrt(ESS),
    // of the sd about sd/sqrt(2 ESS); 4 of each.
    EXPECT_NEAR(p.mean, mu[j], 4 * sd / std::sqrt(p.ess)) << j;
    EXPECT_NEAR(p.sd, sd, 4 * sd / std::sqrt(2 * p.ess)) << j;
    EXPECT_GT(p.ess, 1000) << j;
    EXPECT_LT(p.rhat, 1.01) << j;
  }
  const double corr = S(0, 1) / std::sqrt(S(0, 0) * S(1, 1));
  const double ess = std::min(res.parameters[0].ess, res.parameters[1].ess);
  // The sample correlation's standard error is (1 - rho^2) / sqrt(n).
  EXPECT_NEAR(cov01 / (res.parameters[0].sd * res.parameters[1].sd), corr, 4 * (1 - corr * corr) / std::sqrt(ess));
  // Adaptive Metropolis tunes itself to the target acceptance.
  for (double a : r.acceptance) EXPECT_NEAR(a, 0.234, 0.05);
  EXPECT_TRUE(res.warnings.empty());
}

TEST(Sampling, ThermodynamicIntegrationGivesTheClosedFormEvidence) {
  // y = A theta + noise (sd s), theta ~ N(0, 2^2 I): y ~ N(0, s^2 I + 4 A A^T), whose density
  // at the data is the evidence. phasmid's log L leaves out -(m/2) ln(2 pi s^2).
  LinearGaussian lg;
  const Eigen::MatrixXd& A = lg.A;
  const Eigen::VectorXd& y = lg.y;
  const double s = lg.s;
  const Eigen::MatrixXd C = s * s * Eigen::MatrixXd::Identity(5, 5) + 4.0 * A * A.transpose();
  const double log_z = -0.5 * y.dot(C.ldlt().solve(y)) - 0.5 * std::log(C.determinant()) - 2.5 * std::log(2 * M_PI);
  const double expected = log_z + 2.5 * std::log(2 * M_PI * s * s);
  const FunctionProblem& problem = lg.problem;
  const fit::FitSpec& fs = lg.fs;
  sample::SampleSpec spec;
  spec.sampler.chains = 2, spec.sampler.draws = 20000, spec.sampler.seed = 4;
  spec.sampler.temperatures = 12, spec.sampler.max_temperature = 1e4, spec.sampler.prior_level = true;
  const sample::SampleResult res = sample::run_sampling(problem, fs, spec);
  const sample::Evidence& e = res.evidence;
  ASSERT_TRUE(e.ok) << e.note;
  EXPECT_NEAR(e.log_evidence, expected, 4 * e.error());
  EXPECT_LT(e.error(), 0.1);  // informative: a Bayes factor of 1.1 is resolved
  EXPECT_EQ(e.betas.front(), 1.0);
  EXPECT_EQ(e.betas.back(), 0.0);
  // The prior level's mean log L is E_prior[-1/2 |A theta - y|^2 / s^2], in closed form:
  // -1/2 (|y|^2 + 4 tr(A^T A)) / s^2.
  const double prior_mean = -0.5 * (y.squaredNorm() + 4.0 * (A.transpose() * A).trace()) / (s * s);
  EXPECT_NEAR(e.mean_log_likelihood.back() / prior_mean, 1.0, 0.1);
}

// Bimodal: r = (x^2 - 1) / w with a N(0.3, 1) prior: modes at -1 and +1 (sd w/2) behind a
// barrier of exp(-1 / (2 w^2)) = exp(-200), weighted by the prior. A proposal tuned to one
// mode (sd ~ 5 w/2 at 23 % acceptance in one dimension) would need a jump of 16 sd.
struct Bimodal {
  double w = 0.05;
  fit::Prior prior = fit::parse_prior("normal", "0.3;1", "test");
  FunctionProblem problem{{parameter("x", -3, 3, prior)}, 1, [this](const std::vector<double>& t) {
                            return std::vector<double>{(t[0] * t[0] - 1) / w};
                          }};
  double weight_of_plus() const {  // quadrature of the posterior's mass above 0
    double plus = 0, all = 0;
    for (int i = 0; i <= 6000000; ++i) {
      const double x = -3 + 6.0 * i / 6000000;
      const double r = (x * x - 1) / w;
      const double d = std::exp(-0.5 * r * r - 0.5 * (x - 0.3) * (x - 0.3));
      all += d;
      if (x > 0) plus += d;
    }
    return plus / all;
  }
};

double fraction_above_zero(const sample::SamplerResult& r, size_t from) {
  double n = 0, plus = 0;
  for (size_t c = 0; c < r.chains; ++c)
    for (size_t i = from; i < r.draws; ++i) n += 1, plus += r.at(c, i, 0) > 0;
  return plus / n;
}

TEST(Sampling, ParallelTemperingFindsBothModesWhereAdaptiveMetropolisStaysInOne) {
  Bimodal b;
  const double truth = b.weight_of_plus();
  ASSERT_NEAR(truth, 0.646, 0.01);  // exp(0.6) : 1 from the prior, modes of equal width
  const sample::LogPosterior target(b.problem);
  const Eigen::MatrixXd cov0 = Eigen::MatrixXd::Constant(1, 1, 0.01);
  sample::SamplerOptions am;
  am.chains = 2, am.draws = 20000, am.seed = 5;
  const auto r_am = sample::run_sampler(target, am, {{1.0}, {1.0}}, cov0);
  EXPECT_EQ(fraction_above_zero(r_am, 0), 1.0);  // never crosses the barrier
  sample::SamplerOptions pt = am;
  pt.temperatures = 8, pt.max_temperature = 1000;
  const auto r_pt = sample::run_sampler(target, pt, {{1.0}, {1.0}}, cov0);
  EXPECT_NEAR(fraction_above_zero(r_pt, 2000), truth, 0.05);
  for (double a : r_pt.swap_acceptance) EXPECT_GT(a, 0.05);  // every pair exchanges states
  for (size_t c = 0; c < 2; ++c) {                             // the ladder stays ordered
    EXPECT_EQ(r_pt.betas[c * 8], 1.0);
    for (size_t k = 1; k < 8; ++k) EXPECT_LT(r_pt.betas[c * 8 + k], r_pt.betas[c * 8 + k - 1]);
    EXPECT_DOUBLE_EQ(r_pt.betas[c * 8 + 7], 1.0 / 1000);
  }
}

TEST(Sampling, DrawsDoNotDependOnTheNumberOfThreads) {
  Bimodal b;
  const sample::LogPosterior target(b.problem);
  sample::SamplerOptions o;
  o.chains = 3, o.draws = 500, o.temperatures = 4, o.seed = 9;
  o.threads = 1;
  const auto one = sample::run_sampler(target, o, {{1.0}, {-1.0}, {0.9}}, Eigen::MatrixXd::Constant(1, 1, 0.01));
  o.threads = 3;
  const auto three = sample::run_sampler(target, o, {{1.0}, {-1.0}, {0.9}}, Eigen::MatrixXd::Constant(1, 1, 0.01));
  EXPECT_EQ(one.x, three.x);
  EXPECT_EQ(one.log_likelihood, three.log_likelihood);
  o.seed = 10;
  EXPECT_NE(sample::run_sampler(target, o, {{1.0}, {-1.0}, {0.9}}, Eigen::MatrixXd::Constant(1, 1, 0.01)).x, one.x);
}

TEST(Sampling, RefusesWhatIsNotALikelihood) {
  Bimodal b;
  fit::FitSpec fs;  // absolute_sigma false: residuals scaled by tolerances, not noise
  sample::SampleSpec spec;
  try {
    sample::run_sampling(b.problem, fs, spec);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("[sample] needs absolute_sigma = true in [fit]", 0), 0u);
  }
  fs.absolute_sigma = true;
  spec.sampler.draws = 10;
  try {
    sample::run_sampling(b.problem, fs, spec);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "[sample] draws must be at least 20 (the burn-in rule cuts chains in twentieths)");
  }
}

}  // namespace
}  // namespace phasmid
