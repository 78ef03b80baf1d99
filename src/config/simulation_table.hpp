#pragma once
// [simulation]'s keys and checks applied from any [simulation]-like table, so that settings
// given another way (the Python module's simulate() keywords) are refused exactly as the
// config's keys are: one validation path (docs/python.md "Errors").
#include "config/config.hpp"

namespace phasmid::config {

// Applies `table` over `base`: unknown keys, wrong types and out-of-range values are an Error
// naming cfg.path (and the node's line, where it has one) and the key; an Error too if
// `scenario` takes no [simulation] settings.
SimulationSettings apply_simulation_table(const Config& cfg, const toml::table& table, const scenario::Scenario* scenario,
                                          SimulationSettings base);

}  // namespace phasmid::config
