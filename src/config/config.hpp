#pragma once
// Scenario configs (TOML): one file describes a model and how to run it; every verb reads
// the same file and ignores the sections meant for other verbs (docs/config.md).
#include <toml++/toml.h>

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "model/ode_model.hpp"
#include "solver/simulator.hpp"

namespace phasmid::config {

struct Config {
  std::string path;   // as given (or "embedded:configs/x.toml")
  std::string text;   // the file's text
  toml::table table;
};

// Reads and parses a config file; a path that does not exist on disk but names an embedded
// config ("configs/x.toml" or "x.toml") is taken from the binary. Errors name file:line.
Config load_config(const std::string& path);
Config parse_config(const std::string& text, const std::string& origin);

struct SimulationSettings {
  double t_end_ms = 9000.0;
  double output_dt_ms = 1.0;
  double discard_ms = 0.0;  // transient ignored by gait features
  solver::SolverOptions solver;
};

// Builds the model of [model] and applies [parameters], then the --set overrides, then
// [[triggers]] (config/triggers.hpp).
std::unique_ptr<model::OdeModel> build_model(const Config& cfg, const std::vector<std::string>& sets = {});
SimulationSettings simulation_settings(const Config& cfg);

// Text recorded as the `config` attribute of output files: the config plus the overrides.
std::string resolved_config_text(const Config& cfg, const std::vector<std::string>& sets);

// Helpers for every verb's section parser: "file:line: message" errors.
std::string where(const std::string& origin, const toml::node& node);
std::string where(const Config& cfg, const toml::node& node);
double number(const Config& cfg, const toml::node& node, const std::string& key);
std::string text(const Config& cfg, const toml::node& node, const std::string& key);
// Rejects keys of `table` outside `allowed`, naming file:line, the section and the allowed keys.
void check_keys(const Config& cfg, const toml::table& table, const std::string& section,
                const std::set<std::string>& allowed);

}  // namespace phasmid::config
