#pragma once
// The names of the integrators in configs and on the command line ([simulation] integrator,
// docs/config.md): "cvodes_bdf" and "dopri5" (solver::IntegratorKind).
#include <optional>
#include <string>

#include "solver/solver_options.hpp"

namespace phasmid::solver {

std::optional<IntegratorKind> integrator_from_name(const std::string& name);
std::string integrator_name(IntegratorKind kind);
// The accepted names, quoted and comma-separated (for error messages).
std::string integrator_names();

}  // namespace phasmid::solver
