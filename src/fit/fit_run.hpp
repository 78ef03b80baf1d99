#pragma once
// A whole fit as `phasmid fit` runs it: multistart optimisation, uncertainty at the best
// optimum, profile likelihoods; and the HDF5 layout of the result (docs/fit.md). Starts and
// profile halves are tasks of a parallel::Executor: OpenMP threads, or MPI ranks under mpirun
// (every rank calls run_fit; rank 0 gets the result, docs/cluster.md).
#include <string>
#include <vector>

#include "fit/fit_spec.hpp"
#include "fit/uncertainty.hpp"

namespace phasmid::io {
class H5Writer;
}

namespace phasmid::fit {

struct FitResult {
  MultistartResult multistart;
  Uncertainty uncertainty;
  std::vector<Profile> profiles;
  const FitSummary& best() const { return multistart.runs.at(multistart.best); }
  std::vector<double> estimate;  // linear scale
  bool worker = false;           // this rank was an MPI worker: the result is on rank 0
};

// Never throws for a failing fit (the summaries say why); throws Error for bad input
// (e.g. a profile of a parameter that is not estimated).
FitResult run_fit(const ResidualProblem& problem, const FitSpec& spec);

// Human summary: the optimiser's lines, then one line per parameter (estimate +- SE).
std::string format_result(const ResidualProblem& problem, const FitResult& result);

// /fit/... (docs/fit.md), /trajectory (best fit), /parameters, /features.
void write_fit_h5(io::H5Writer& out, const ResidualProblem& problem, const FitSpec& spec, const FitResult& result);

}  // namespace phasmid::fit
