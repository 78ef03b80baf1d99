#pragma once
// Multistart: the nominal start plus starts drawn from a Latin hypercube or Sobol sequence
// over the scaled bounds, optimised in parallel (OpenMP threads, or MPI ranks through a
// parallel::Executor: one local optimisation per task); deterministic for a given seed (each
// start's result depends only on its start point, and travels between ranks bit for bit).
#include <cstdint>
#include <string>
#include <vector>

#include "parallel/executor.hpp"
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
  std::vector<parallel::WorkerStats> work;  // starts per thread or worker rank
};

// On OpenMP threads (ms.threads).
MultistartResult multistart(const ResidualProblem& problem, const OptimizerOptions& options, const MultistartOptions& ms);
// On `executor`; on an MPI worker rank the result is empty (rank 0 holds it).
MultistartResult multistart(const ResidualProblem& problem, const OptimizerOptions& options, const MultistartOptions& ms,
                            parallel::Executor& executor);

// A FitSummary as bytes and back, every double bit for bit.
std::string encode_summary(const FitSummary& s);
FitSummary decode_summary(const std::string& bytes);

}  // namespace phasmid::fit
