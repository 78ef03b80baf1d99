#pragma once
// [simulation] and [simulation.expert] (docs/config.md): read from any [simulation]-like table,
// so that settings given another way (the Python module's simulate() keywords) are checked by
// the same code as the config's keys (docs/python.md "Errors"), then resolved by the model
// kind (Scenario::integration), the one place that decides how a kind integrates.
#include <optional>
#include <set>
#include <string>

#include "config/config.hpp"

namespace phasmid::config {

// What a [simulation] table asked; an empty optional is "not given".
struct SimulationRequest {
  std::optional<double> t_end_ms, output_dt_ms, discard_ms;
  scenario::IntegrationRequest integration;
};

// The keys of [simulation] and of its sub-table [simulation.expert].
const std::set<std::string>& simulation_keys();
const std::set<std::string>& expert_keys();

// Reads `table` over `base`: unknown keys, wrong types and out-of-range values are an Error
// naming cfg.path (and the node's line, where it has one) and the key; an Error too if
// `scenario` takes no [simulation] settings.
SimulationRequest read_simulation_table(const Config& cfg, const toml::table& table, const scenario::Scenario* scenario,
                                        SimulationRequest base);
// The config's [simulation] (empty request without one).
SimulationRequest simulation_request(const Config& cfg, const scenario::Scenario* scenario);
// The run times (RunSettings' defaults where not given, checked together) and the scenario's
// integration of the request (without a scenario: one system on CVODES BDF). Errors name
// `where` ("file:line: [simulation]", "simulate()") and the option.
SimulationSettings resolve_simulation(const SimulationRequest& request, const scenario::Scenario* scenario,
                                      const std::string& where);

}  // namespace phasmid::config
