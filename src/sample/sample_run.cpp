#include "sample/sample_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <random>
#include <sstream>

#include "common/error.hpp"
#include "fit/fit_run.hpp"
#include "fit/uncertainty.hpp"
#include "io/h5_file.hpp"
#include "sample/diagnostics.hpp"

namespace phasmid::sample {

Start parse_start(const std::string& s) {
  if (s == "prior") return Start::Prior;
  if (s == "fit") return Start::Fit;
  throw Error("[sample] start must be \"prior\" or \"fit\", got \"" + s + "\"");
}

const char* start_name(Start s) { return s == Start::Prior ? "prior" : "fit"; }

void check_sampling_problem(const fit::ResidualProblem& problem, const fit::FitSpec& fit_spec) {
  if (problem.num_parameters() == 0) throw Error("[sample]: no estimated parameter to sample ([fit.parameters] or --parameters)");
  if (!fit_spec.absolute_sigma)
    throw Error("[sample] needs absolute_sigma = true in [fit]: only residuals scaled by their true noise make "
                "-1/2 sum r^2 a log-likelihood");
}

namespace {
// One draw of the prior's own law: of x for parameterScale* types, of theta else.
double draw_law(const fit::Prior& p, std::mt19937_64& rng) {
  using fit::PriorType;
  auto laplace = [&] {  // location a, scale b: an exponential with a random sign
    const double e = std::exponential_distribution<double>(1.0 / p.b)(rng);
    return std::uniform_real_distribution<double>()(rng) < 0.5 ? p.a - e : p.a + e;
  };
  switch (p.type) {
    case PriorType::ParameterScaleUniform:
    case PriorType::Uniform: return std::uniform_real_distribution<double>(p.a, p.b)(rng);
    case PriorType::ParameterScaleNormal:
    case PriorType::Normal: return std::normal_distribution<double>(p.a, p.b)(rng);
    case PriorType::ParameterScaleLaplace:
    case PriorType::Laplace: return laplace();
    case PriorType::LogNormal: return std::exp(std::normal_distribution<double>(p.a, p.b)(rng));
    case PriorType::LogLaplace: return std::exp(laplace());
  }
  return NAN;
}

// One draw of parameter p's prior on its scale, truncated to its bounds (by rejection).
double draw_prior(const fit::FitParameter& p, std::mt19937_64& rng) {
  const double lo = fit::to_scaled(p.scale, p.lower), hi = fit::to_scaled(p.scale, p.upper);
  if (!p.prior.declared) return std::uniform_real_distribution<double>(lo, hi)(rng);
  const bool on_x = fit::on_parameter_scale(p.prior.type);
  for (int attempt = 0; attempt < 100000; ++attempt) {
    const double v = draw_law(p.prior, rng);
    const double x = on_x ? v : fit::to_scaled(p.scale, v);
    if (x >= lo && x <= hi) return x;
  }
  throw Error(p.origin + ": parameter '" + p.id + "': its prior puts almost no mass within [lowerBound, upperBound]");
}

std::vector<std::vector<double>> prior_starts(const LogPosterior& target, const SampleSpec& spec) {
  std::seed_seq seq{static_cast<std::uint32_t>(spec.sampler.seed), static_cast<std::uint32_t>(spec.sampler.seed >> 32), 0x5747u};
  std::mt19937_64 rng(seq);
  std::vector<std::vector<double>> starts;
  const auto& est = target.problem().estimated();
  for (std::size_t c = 0; c < spec.sampler.chains; ++c) {
    for (int attempt = 0;; ++attempt) {
      std::vector<double> x;
      for (const auto& p : est) x.push_back(draw_prior(p, rng));
      if (std::isfinite(target(x).tempered(1.0))) {
        starts.push_back(x);
        break;
      }
      if (attempt == 99) throw Error("[sample] start = \"prior\": 100 draws of the prior gave no model run that succeeded");
    }
  }
  return starts;
}

Eigen::MatrixXd box_covariance(const fit::ResidualProblem& problem) {
  const auto lo = problem.lower(), hi = problem.upper();
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(static_cast<long>(lo.size()), static_cast<long>(lo.size()));
  for (std::size_t j = 0; j < lo.size(); ++j) c(static_cast<long>(j), static_cast<long>(j)) = std::pow((hi[j] - lo[j]) / 20.0, 2);
  return c;
}

void print_progress(std::size_t done, std::size_t total) {
  if (done == total || done % std::max<std::size_t>(1, total / 10) == 0)
    std::cerr << "phasmid sample: step " << done << " of " << total << "\n";
}
}  // namespace

SampleResult run_sampling(const fit::ResidualProblem& problem, const fit::FitSpec& fit_spec, const SampleSpec& spec) {
  check_sampling_problem(problem, fit_spec);
  std::string why;
  if (!spec.sampler.IsValid(&why)) throw Error("[sample] " + why);
  const LogPosterior target(problem);
  std::vector<std::vector<double>> starts;
  Eigen::MatrixXd cov0 = box_covariance(problem);
  if (spec.start == Start::Fit) {
    const fit::FitResult fr = fit::run_fit(problem, fit_spec);
    if (!fr.best().usable) throw Error("[sample] start = \"fit\": the fit found no usable optimum (" + fr.best().termination + ")");
    starts.assign(spec.sampler.chains, fr.best().x);
    if (fr.uncertainty.ok && fr.uncertainty.covariance_scaled.allFinite()) cov0 = fr.uncertainty.covariance_scaled;
  } else {
    starts = prior_starts(target, spec);
  }
  SampleResult result;
  result.start_x = starts[0];
  const std::size_t total = spec.sampler.draws;
  SamplerProgress progress;
  if (spec.progress) progress = [total](std::size_t done) { print_progress(done, total); };
  result.run = run_sampler(target, spec.sampler, starts, cov0, progress);
  analyse(problem, result);
  return result;
}

namespace {
double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const std::size_t i = static_cast<std::size_t>(pos);
  return i + 1 < v.size() ? v[i] + (pos - static_cast<double>(i)) * (v[i + 1] - v[i]) : v.back();
}

// The chains of parameter j from draw `from` on (scaled).
Chains chains_of(const SamplerResult& r, std::size_t j, std::size_t from) {
  Chains out(r.chains);
  for (std::size_t c = 0; c < r.chains; ++c)
    for (std::size_t i = from; i < r.draws; ++i) out[c].push_back(r.at(c, i, j));
  return out;
}
}  // namespace

void analyse(const fit::ResidualProblem& problem, SampleResult& result) {
  const SamplerResult& r = result.run;
  std::vector<Chains> all;
  for (std::size_t j = 0; j < r.dim; ++j) all.push_back(chains_of(r, j, 0));
  result.burn_in = burn_in(all);
  // Diagnostics need draws: with no stationary start found, they describe the last half.
  const std::size_t from = std::min(result.burn_in, r.draws / 2);
  if (result.burn_in >= r.draws)
    result.warnings.push_back("no burn-in found: every chain still drifts (Geweke); statistics are of the last half, run longer");
  if (r.prior_level) {
    result.evidence = thermodynamic_integration(r, std::max(result.burn_in, r.ladder_fixed_from));
    if (!result.evidence.ok) result.warnings.push_back("no model evidence: " + result.evidence.note);
  }
  const auto names = problem.parameter_names();
  result.parameters.clear();
  for (std::size_t j = 0; j < r.dim; ++j) {
    const Chains ch = chains_of(r, j, from);
    std::vector<double> lin;
    for (const auto& c : ch)
      for (double x : c) lin.push_back(fit::from_scaled(problem.estimated()[j].scale, x));
    ParameterSummary s;
    const Moments mo = moments(lin);
    s.mean = mo.mean, s.sd = std::sqrt(mo.variance);
    s.median = quantile(lin, 0.5), s.q025 = quantile(lin, 0.025), s.q975 = quantile(lin, 0.975);
    s.ess = effective_sample_size(ch);
    s.rhat = r.chains > 1 || ch[0].size() >= 8 ? split_rhat(ch) : NAN;
    for (auto& w : diagnostic_warnings(names[j], s.ess, s.rhat)) result.warnings.push_back(w);
    result.parameters.push_back(s);
  }
}

std::string format_result(const fit::ResidualProblem& problem, const SampleSpec& spec, const SampleResult& res) {
  const SamplerResult& r = res.run;
  std::ostringstream os;
  double acc = 0;
  for (double a : r.acceptance) acc += a;
  os << "phasmid sample: " << r.chains << " chain(s) x " << r.draws << " steps" << (r.temperatures > 1 ? " x " + std::to_string(r.temperatures) + " temperatures" : "")
     << ", burn-in " << res.burn_in << ", acceptance " << acc / double(r.chains) << ", start " << start_name(spec.start);
  if (r.failed_evaluations) os << ", " << r.failed_evaluations << " failed model runs (rejected)";
  os << "\n";
  char line[256];
  std::snprintf(line, sizeof line, "  %-34s %12s %11s %12s %12s %8s %7s  %s\n", "parameter", "mean", "sd", "2.5%", "97.5%", "ESS", "R-hat", "unit");
  os << line;
  const auto names = problem.parameter_names();
  for (std::size_t j = 0; j < res.parameters.size(); ++j) {
    const ParameterSummary& s = res.parameters[j];
    std::snprintf(line, sizeof line, "  %-34s %12.5g %11.4g %12.5g %12.5g %8.0f %7.4f  %s\n", names[j].c_str(), s.mean, s.sd, s.q025,
                  s.q975, s.ess, s.rhat, problem.parameter_unit(j).c_str());
    os << line;
  }
  if (res.evidence.ok) {
    std::snprintf(line, sizeof line, "  log evidence %.6g +- %.2g (Monte Carlo %.2g, discretisation %.2g; up to the fixed noises' constant)\n",
                  res.evidence.log_evidence, res.evidence.error(), res.evidence.mc_error, res.evidence.discretisation_error);
    os << line;
  }
  for (const auto& w : res.warnings) os << "phasmid sample: warning: " << w << "\n";
  return os.str();
}

}  // namespace phasmid::sample
