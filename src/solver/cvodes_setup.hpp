#pragma once
// Setup shared by the whole-system and the partitioned integrators: failing CVODES setup calls
// become SolverErrors, and SolverOptions' step controls are applied the same way to every
// CVODES memory (so an option added here reaches both).
#include "solver/simulator.hpp"

namespace phasmid::solver {

// Throws SolverError("CVODES setup failed in <what> (flag N)") for a negative flag.
void check_cvodes(int flag, const char* what);

// max_steps, max_step_ms, max_order and stability-limit detection of `options`, and a silent
// error handler (phasmid reports failures itself), on the CVODES memory `cvode_mem`.
void apply_step_options(void* cvode_mem, const SolverOptions& options);

}  // namespace phasmid::solver
