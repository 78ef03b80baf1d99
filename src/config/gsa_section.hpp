#pragma once
// The [gsa] section of a scenario config (docs/gsa.md), read into a gsa::GsaSpec:
//   method = "sobol" | "morris", features = ["name", ...] (required), seed, bootstrap (resamples),
//   confidence; Sobol': N (base sample size), second_order, scramble, skip;
//   Morris: trajectories (r), levels (p, even), pool (Campolongo selection; 0: none).
// The parameters and their ranges are the config's [[sweep.parameter]] tables
// (config/sweep_section.hpp, parse_sweep_ranges). Every error names file:line and the key.
#include <string>
#include <vector>

#include "config/config.hpp"
#include "features/features.hpp"
#include "gsa/gsa_run.hpp"

namespace phasmid::config {

// `catalogue`: the features the scenario can report; a feature name outside it is an error
// naming the nearest one.
gsa::GsaSpec parse_gsa_section(const Config& cfg, const std::vector<features::FeatureInfo>& catalogue);

// The design `spec` gives over `n_parameters` ranges fits: Sobol' at most kSobolMaxDim / 2
// parameters, and at most the sweep's 1e7 points (N x (2D + 2) or N x (D + 2); Morris
// trajectories x (D + 1)). Errors name file:line of the key (or the 17th parameter).
void check_gsa_design(const Config& cfg, const gsa::GsaSpec& spec, std::size_t n_parameters);

}  // namespace phasmid::config
