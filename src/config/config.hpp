#pragma once
// Scenario configs (TOML): one file describes a model and how to run it; every verb reads
// the same file and ignores the sections meant for other verbs (docs/config.md). `[model] type`
// selects a registered model kind (scenario/registry.hpp); [parameters] and --set give values
// to its named parameters.
#include <memory>
#include <string>
#include <vector>

#include "config/toml_util.hpp"
#include "scenario/scenario.hpp"

namespace phasmid::model {
class OdeModel;
}

namespace phasmid::config {

using SimulationSettings = scenario::RunSettings;

// Makes the scenario of [model] (its kind's factory), then applies [parameters], then the
// --set overrides, then [[triggers]] (config/triggers.hpp; ODE kinds only). Errors are one
// line naming file:line and the key, or the --set assignment.
std::unique_ptr<scenario::Scenario> build_scenario(const Config& cfg, const std::vector<std::string>& sets = {});
// The same for kinds that are one ODE system, handing over the model itself (tests, benchmarks
// and the analyses that drive the solver directly); an Error for other kinds.
std::unique_ptr<model::OdeModel> build_model(const Config& cfg, const std::vector<std::string>& sets = {});
// [simulation] (docs/config.md) resolved by the scenario's kind (Scenario::integration; without
// a scenario, one system on CVODES BDF); an Error if the section is given for a kind it does
// not apply to, or names a setting the kind refuses.
SimulationSettings simulation_settings(const Config& cfg, const scenario::Scenario* scenario = nullptr);
// The same for analyses whose runs are CVODES BDF on the whole system (forward sensitivities,
// continuation): the kind's setting for integrator = "cvodes_bdf" unless [simulation] names an
// integrator, so that its tolerances are the ones the kind gives BDF (docs/solver.md).
SimulationSettings bdf_simulation_settings(const Config& cfg, const scenario::Scenario* scenario);

// Text recorded as the `config` attribute of output files: the config plus the overrides.
std::string resolved_config_text(const Config& cfg, const std::vector<std::string>& sets);

}  // namespace phasmid::config
