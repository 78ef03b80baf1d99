#pragma once
// The [sweep] section of a scenario config (docs/sweep.md), read into a sweep::SweepSpec.
#include <cstddef>

#include "config/config.hpp"
#include "model/parameters.hpp"
#include "sweep/sweep_spec.hpp"

namespace phasmid::sweep {

// Parses and validates [sweep] against the model's parameters (names, admissible ranges);
// every error names file:line. t_end_ms / discard_ms default to [simulation]'s.
SweepSpec parse_sweep(const config::Config& cfg, const model::ParameterSet& params,
                      const config::SimulationSettings& sim);

// The [sweep] section of an analysis that supplies its own points (Design::Explicit, e.g.
// `phasmid gsa`): the [[sweep.parameter]] ranges (lower, upper, scale) and the run length only;
// design, points, seed, options and per-parameter values are refused. The spec has no points
// yet: give them with set_unit_points.
SweepSpec parse_sweep_ranges(const config::Config& cfg, const model::ParameterSet& params,
                             const config::SimulationSettings& sim);

// The config with combination `combo`'s option values written into [model].
config::Config config_for(const config::Config& cfg, const SweepSpec& spec, std::size_t combo);

}  // namespace phasmid::sweep
