#pragma once
// The HDF5 input readers both HDF5 fuzz targets (h5_input: bytes; h5_content: well-formed files
// with hostile content) put a file through: report's extraction (every panel), the /features
// and /sweep/ranges readers, and a shard as `merge` reads it (merged into a scratch output).
#include <cstdio>
#include <string>

#include "config/config.hpp"
#include "config/sweep_inputs.hpp"
#include "features/features.hpp"
#include "fuzz_input.hpp"
#include "io/h5_file.hpp"
#include "report/report.hpp"
#include "sweep/ranges.hpp"
#include "sweep/sweep_shard.hpp"

namespace phasmid::fuzz {

inline void read_h5_as_phasmid_does(const std::string& path) {
  attempt([&] { report::extract(path); });
  attempt([&] {
    io::H5Reader in(path);
    features::read_features_h5(in);
    sweep::read_ranges_h5(in);
  });
  const std::string merged = scratch_path("merged.h5");
  const auto inputs_of = [](const std::string& text, const std::string& origin, const std::vector<std::string>& sets) {
    return config::sweep_inputs(config::parse_config(text, origin), sets);
  };
  attempt([&] { sweep::merge_shards({path}, merged, "fuzz", inputs_of); });
  std::remove(merged.c_str());
}

}  // namespace phasmid::fuzz
