#pragma once
// Reading TOML scenario configs: the parsed file and the helpers every section parser uses,
// so that every error names file:line and the key. No model or solver types here: model kinds
// (src/scenario/kinds) and analyses' section parsers use it without depending on each other.
#include <toml++/toml.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "common/nearest.hpp"

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

// "file:line" of a node (the file alone where the node has no position).
std::string where(const std::string& origin, const toml::node& node);
std::string where(const Config& cfg, const toml::node& node);
// Typed values: a wrong type is an error naming file:line and the key. Numbers must be finite
// (TOML's inf and nan are refused); number_in also bounds them to [lo, hi].
double number(const Config& cfg, const toml::node& node, const std::string& key);
double number_in(const Config& cfg, const toml::node& node, const std::string& key, double lo, double hi);

// Bounds of every run's times (docs/config.md "Limits"): documented choices that keep a run's
// memory and time finite, not model numbers.
inline constexpr double kMaxTEndMs = 1e7;         // ms: 2.8 h of simulated time
inline constexpr double kMinOutputDtMs = 1e-3;    // ms: 1 us, far below the model's fastest dynamics
inline constexpr double kMaxOutputSamples = 1e7;  // t_end_ms / output_dt_ms stored samples per run
// An Error at `where` unless 0 < t_end_ms <= kMaxTEndMs, 0 <= discard_ms < t_end_ms,
// output_dt_ms >= kMinOutputDtMs and (t_end_ms - discard_ms) / output_dt_ms <= kMaxOutputSamples.
void check_run_times(double t_end_ms, double output_dt_ms, double discard_ms, const std::string& where);

// The top-level sections a config may have; anything else is an error suggesting the nearest.
// Adding a section ([gsa], [continuation], ...) is one line in known_sections() (toml_util.cpp).
const std::vector<std::string>& known_sections();
std::string text(const Config& cfg, const toml::node& node, const std::string& key);
bool boolean(const Config& cfg, const toml::node& node, const std::string& key);
// Rejects keys of `table` outside `allowed`, naming file:line, the section, the nearest allowed
// key and the allowed keys.
void check_keys(const Config& cfg, const toml::table& table, const std::string& section,
                const std::set<std::string>& allowed);
// The element of `candidates` closest to `word` by edit distance (common/nearest.hpp).
using phasmid::nearest;

// Dotted names of a table's leaves: quoted dotted keys ("middle.fti.b_v" = 12.5) and TOML
// dotted keys or sub-tables (middle.fti.b_v = 12.5) give the same name.
std::vector<std::pair<std::string, const toml::node*>> flatten(const toml::table& table);

}  // namespace phasmid::config
