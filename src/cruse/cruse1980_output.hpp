#pragma once
// HDF5 and JSON output of Cruse (1980) runs (layout in docs/cruse1980.md).
#include <nlohmann/json.hpp>
#include <string>

#include "cruse/cruse1980_features.hpp"

namespace phasmid::cruse {

nlohmann::json features_json(const Features& f);
void write_run(const std::string& path, const LoadedConfig& config, const Trajectory& run, const Features& f,
               const std::string& command);

}  // namespace phasmid::cruse
