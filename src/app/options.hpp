#pragma once
// Options that mean the same in every verb (docs/cli.md): the config argument, -o/--output,
// --set, -q/--quiet, -j/--threads and --json, with one help text each.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "parallel/executor.hpp"

namespace phasmid::app {

inline void add_config_arg(CLI::App& sub, std::string& config, const std::string& what = "scenario config (TOML)") {
  sub.add_option("config", config, what + "; a file, or the name of a shipped config")->required();
}
inline void add_output(CLI::App& sub, std::string& out, const std::string& fallback) {
  sub.add_option("-o,--output", out, "output file (default " + fallback + ")");
}
inline void add_sets(CLI::App& sub, std::vector<std::string>& sets) {
  sub.add_option("--set", sets, "override a parameter: NAME=VALUE (repeatable; after [parameters])");
}
inline void add_quiet(CLI::App& sub, bool& quiet) {
  sub.add_flag("-q,--quiet", quiet, "no progress line or summary on stderr");
}
inline void add_threads(CLI::App& sub, int& threads) {
  sub.add_option("-j,--threads", threads,
                 "worker threads (default: OMP_NUM_THREADS or all cores; per rank under mpirun: OMP_NUM_THREADS or 1)")
      ->check(CLI::Range(0, parallel::kMaxThreads));  // says the limit (NonNegativeNumber printed DBL_MAX in full)
}
// An integer option whose absence is not a value (an override's std::optional); its range is
// checked where the override is applied (fit::check_overrides, config::sample_spec), not
// here, so that other front ends (Python's fit()) get the same message.
inline void add_long(CLI::App& sub, const std::string& name, std::optional<long>& out, const std::string& help) {
  sub.add_option_function<long>(name, [&out](const long& v) { out = v; }, help);
}
inline void add_json(CLI::App& sub, bool& json) { sub.add_flag("--json", json, "print the results as JSON on stdout"); }

}  // namespace phasmid::app
