// phasmid features RUN.h5 [--json]: the gait features stored by `simulate` under /features.
#include <cmath>
#include <cstdio>
#include <iostream>

#include "app/verb.hpp"
#include "app/write_output.hpp"
#include "common/error.hpp"
#include "features/features.hpp"
#include "io/h5_file.hpp"

namespace phasmid::app {
namespace {

int run_features(const std::string& path, bool json) {
  io::H5Reader in(path);  // throws "no such file" / "not an HDF5 file"
  bool phasmid_file = true;
  try {
    in.read_string_attribute("/", "phasmid_version");
  } catch (const Error&) {
    phasmid_file = false;
  }
  if (!phasmid_file) throw Error(path + ": not a phasmid file (no phasmid_version attribute)");
  std::vector<features::Feature> fs = features::read_features_h5(in);
  if (json) {
    print_features_json(fs);
    return 0;
  }
  size_t w = 7;
  for (auto& f : fs) w = std::max(w, f.name.size());
  std::printf("%-*s  %14s  %s\n", static_cast<int>(w), "feature", "value", "unit");
  for (auto& f : fs) std::printf("%-*s  %14.6g  %s\n", static_cast<int>(w), f.name.c_str(), f.value, f.unit.c_str());
  return 0;
}

const RegisterVerb reg{{"features", "Print the features stored in a run file (period, phase durations and ratios, extremal angles, ...)",
                        [](CLI::App& sub) -> std::function<int()> {
                          auto path = std::make_shared<std::string>();
                          auto json = std::make_shared<bool>(false);
                          sub.add_option("RUN", *path, "HDF5 file written by phasmid simulate")->required();
                          sub.add_flag("--json", *json, "print a JSON list of {name, value, unit}");
                          return [path, json] { return run_features(*path, *json); };
                        }}};

}  // namespace
}  // namespace phasmid::app
