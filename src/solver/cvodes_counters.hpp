#pragma once
// CVODES' work counters of one integrator since its last (re)start, added to a run's totals
// (CVodeReInit resets them, so both simulators add them before each restart and at the end).
#include "solver/simulator.hpp"

namespace phasmid::solver {

// Adds error-test failures, Newton iterations and failures, linear-solver setups, RHS and
// Jacobian evaluations of the CVODES memory `cvode_mem` to `into` (steps are left to the caller).
void add_cvodes_counters(void* cvode_mem, SolverStats& into);

}  // namespace phasmid::solver
