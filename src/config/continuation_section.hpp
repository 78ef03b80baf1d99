#pragma once
// The [continuation] section of a scenario config (docs/continuation.md): the parameter and its
// range, step control, the Poincare section, shooting tolerances and the tracked features.
#include "config/config.hpp"
#include "continuation/continuation.hpp"

namespace phasmid::config {

// Reads [continuation] (keys: parameter, range = [start, end], initial_step, min_step, max_step,
// max_points, section = "<leg>.liftoff" | "<leg>.touchdown" | "angle_max" or section_state,
// section_level, section_direction = "rising" | "falling", transient_ms, max_period_ms,
// tolerance, residual_rtol, neutral_tolerance, max_iterations, features = [names], feature_cycles, max_period_factor,
// hopf_amplitude_fraction, locate_iterations, and a table linked = { "<parameter>" = [from, to] }
// of parameters moved with it) with the solver of `sim` ([simulation]).
// Errors name file:line and the key; an Error naming the file if the section is missing.
continuation::ContinuationOptions continuation_options(const Config& cfg, const model::OdeModel& model,
                                                       const SimulationSettings& sim);

}  // namespace phasmid::config
