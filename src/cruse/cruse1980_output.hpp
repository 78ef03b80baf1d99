#pragma once
// HDF5 and JSON output of Cruse (1980) runs (layout in docs/cruse1980.md).
#include <nlohmann/json.hpp>
#include <string>

#include "cruse/cruse1980_features.hpp"

namespace phasmid {
namespace io {
class H5Writer;
}

namespace cruse {

nlohmann::json features_json(const Features& f);
// The config text followed by every resolved parameter value as comments.
std::string resolved_config(const LoadedConfig& config);
// /trajectory, /events, /parameters and /features of one run (no root attributes).
void write_run_contents(io::H5Writer& w, const Parameters& p, const Trajectory& run, const Features& f);
void write_run(const std::string& path, const LoadedConfig& config, const Trajectory& run, const Features& f,
               const std::string& command);

}  // namespace cruse
}  // namespace phasmid
