#pragma once
// What `phasmid sweep` runs, read from a config: the [sweep] design over the scenario's
// parameters, a factory of the scenario of each [sweep] option combination, the run settings
// and the resolved config text (docs/sweep.md).
#include <functional>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "sweep/sweep_runner.hpp"

namespace phasmid::config {

// Errors name file:line (a combination that cannot be built names the option value's line).
sweep::SweepInputs sweep_inputs(const Config& cfg, const std::vector<std::string>& sets);

// The same with the design read by `design` instead of sweep::parse_sweep (e.g. `phasmid gsa`,
// whose points come from [gsa]).
using DesignReader = std::function<sweep::SweepSpec(const Config&, const model::ParameterSet&, const SimulationSettings&)>;
sweep::SweepInputs sweep_inputs(const Config& cfg, const std::vector<std::string>& sets, const DesignReader& design);

}  // namespace phasmid::config
