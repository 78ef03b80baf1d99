#pragma once
// What `phasmid gsa` runs, read from a config (docs/gsa.md): the [gsa] settings, the design
// they give over the [[sweep.parameter]] ranges, and the sweep whose points are that design's
// rows. Shared by the verb, the tests and the benchmark, so all of them run the same path.
#include <string>
#include <vector>

#include "config/config.hpp"
#include "gsa/gsa_run.hpp"
#include "sweep/sweep_runner.hpp"

namespace phasmid::config {

struct GsaInputs {
  sweep::SweepInputs sweep;                     // spec.points = the design, in parameter units
  gsa::GsaSpec spec;                            // [gsa]
  gsa::GsaResult design;                        // method, parameters, options, design; no features yet
  std::vector<features::FeatureInfo> catalogue;  // the scenario's features (names, units)
};

// Errors name file:line ([gsa] keys, [[sweep.parameter]] ranges, unknown features).
GsaInputs gsa_inputs(const Config& cfg, const std::vector<std::string>& sets);

// After the sweep of `in` finished into `path`: reads its outputs, analyses every feature of
// [gsa] and writes /gsa into the same file (atomically). Returns the result.
gsa::GsaResult analyse_and_write(const GsaInputs& in, const std::string& path, const std::string& command);

}  // namespace phasmid::config
