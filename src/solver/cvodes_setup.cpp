#include "solver/cvodes_setup.hpp"

#include <cvodes/cvodes.h>

#include <string>

#include "common/error.hpp"

namespace phasmid::solver {

void check_cvodes(int flag, const char* what) {
  if (flag < 0) throw SolverError(std::string("CVODES setup failed in ") + what + " (flag " + std::to_string(flag) + ")");
}

void apply_step_options(void* mem, const SolverOptions& options) {
  check_cvodes(CVodeSetMaxNumSteps(mem, options.max_steps), "CVodeSetMaxNumSteps");
  check_cvodes(CVodeSetErrHandlerFn(mem, [](int, const char*, const char*, char*, void*) {}, nullptr), "silence");
  if (options.max_step_ms > 0) check_cvodes(CVodeSetMaxStep(mem, options.max_step_ms), "CVodeSetMaxStep");
  if (options.max_order > 0) check_cvodes(CVodeSetMaxOrd(mem, options.max_order), "CVodeSetMaxOrd");
  if (options.stability_limit_detection) check_cvodes(CVodeSetStabLimDet(mem, SUNTRUE), "CVodeSetStabLimDet");
}

}  // namespace phasmid::solver
