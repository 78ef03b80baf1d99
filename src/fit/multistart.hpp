#pragma once
// Multistart: the nominal start plus starts drawn from a Latin hypercube or Sobol sequence
// over the scaled bounds, optimised in parallel (OpenMP); deterministic for a given seed
// (each start's result depends only on its start point).
#include <cstdint>
#include <vector>

#include "fit/optimizer.hpp"
#include "fit/start_points.hpp"

namespace phasmid::fit {

struct MultistartOptions {
  size_t starts = 1;  // total number of starts including the nominal one; 1: a single fit
  Sampling sampling = Sampling::LatinHypercube;
  std::uint64_t seed = 1;
  int threads = 0;    // 0: OpenMP default
};

struct MultistartResult {
  std::vector<FitSummary> runs;  // in start order; runs[0] starts at the nominal values
  size_t best = 0;               // index of the lowest final cost among usable runs
};

MultistartResult multistart(const ResidualProblem& problem, const OptimizerOptions& options, const MultistartOptions& ms);

}  // namespace phasmid::fit
