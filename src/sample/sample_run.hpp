#pragma once
// A whole sampling run as `phasmid sample` runs it (docs/sampling.md): start points, the
// initial proposal, the sampler, the diagnostics and the posterior summary; and its HDF5
// layout /sample. The problem is the one the fit builds from [fit] (targets, recordings,
// observables, noise), its parameters' priors from the parameter table.
#include <cstdint>
#include <string>
#include <vector>

#include "fit/fit_spec.hpp"
#include "sample/evidence.hpp"
#include "sample/sampler.hpp"

namespace phasmid::io {
class H5Writer;
}

namespace phasmid::sample {

enum class Start {
  Prior,  // each chain from its own draw of the prior (within the bounds)
  Fit,    // every chain from the fit's optimum; the fit's covariance is the first proposal
};
Start parse_start(const std::string& s);  // "prior" | "fit"; throws Error otherwise
const char* start_name(Start s);

struct SampleSpec {
  SamplerOptions sampler;
  Start start = Start::Prior;
  bool progress = false;  // a progress line on stderr
};

struct ParameterSummary {  // of the draws after burn-in, linear scale
  double mean = 0, sd = 0, median = 0, q025 = 0, q975 = 0;
  double ess = 0, rhat = 0;  // of the scaled draws
};

struct SampleResult {
  SamplerResult run;
  std::size_t burn_in = 0;
  std::vector<ParameterSummary> parameters;  // per estimated parameter
  std::vector<std::string> warnings;         // one line each (docs/sampling.md)
  std::vector<double> start_x;               // the chains' first start (scaled)
  Evidence evidence;                         // with a prior level (SamplerOptions::prior_level)
};

// Throws Error if the fit is not a likelihood (absolute_sigma false) or the problem has no
// parameter to sample.
void check_sampling_problem(const fit::ResidualProblem& problem, const fit::FitSpec& fit_spec);

// fit_spec is used only for Start::Fit (the fit that gives the start).
SampleResult run_sampling(const fit::ResidualProblem& problem, const fit::FitSpec& fit_spec, const SampleSpec& spec);

// The diagnostics and summary of a finished run (also for tests).
void analyse(const fit::ResidualProblem& problem, SampleResult& result);

std::string format_result(const fit::ResidualProblem& problem, const SampleSpec& spec, const SampleResult& r);
void write_sample_h5(io::H5Writer& out, const fit::ResidualProblem& problem, const SampleSpec& spec, const SampleResult& r);

}  // namespace phasmid::sample
