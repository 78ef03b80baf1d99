#include "solver/cvodes_counters.hpp"

#include <cvodes/cvodes.h>

#include <utility>

namespace phasmid::solver {

void add_cvodes_counters(void* cvode_mem, SolverStats& into) {
  using Getter = int (*)(void*, long*);
  const std::pair<Getter, long SolverStats::*> counters[] = {
      {CVodeGetNumErrTestFails, &SolverStats::error_test_failures},
      {CVodeGetNumNonlinSolvIters, &SolverStats::newton_iterations},
      {CVodeGetNumNonlinSolvConvFails, &SolverStats::newton_failures},
      {CVodeGetNumLinSolvSetups, &SolverStats::linear_setups},
      {CVodeGetNumRhsEvals, &SolverStats::rhs_evals},
      {CVodeGetNumJacEvals, &SolverStats::jac_evals}};
  for (const auto& [get, field] : counters) {
    long v = 0;
    get(cvode_mem, &v);
    into.*field += v;
  }
}

}  // namespace phasmid::solver
