#pragma once
// The names of the integrators in configs and on the command line ([simulation] integrator,
// docs/config.md): "cvodes_bdf", "cvodes_adams", "erk_bs3", "erk_dp5", "erk_verner65",
// "erk_fehlberg78", "dopri5" (solver::IntegratorKind).
#include <optional>
#include <string>

#include "solver/simulator.hpp"

namespace phasmid::solver {

std::optional<IntegratorKind> integrator_from_name(const std::string& name);
std::string integrator_name(IntegratorKind kind);
// The accepted names, quoted and comma-separated (for error messages).
std::string integrator_names();

}  // namespace phasmid::solver
