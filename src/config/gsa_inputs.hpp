#pragma once
// What `phasmid gsa` runs, read from a config (docs/gsa.md): the [gsa] settings, the design
// they give over the [[sweep.parameter]] ranges, and the sweep whose points are that design's
// rows. gsa/gsa_job.hpp runs them.
#include <string>
#include <vector>

#include "config/config.hpp"
#include "gsa/gsa_job.hpp"

namespace phasmid::config {

// Errors name file:line ([gsa] keys, [[sweep.parameter]] ranges, unknown features).
gsa::GsaInputs gsa_inputs(const Config& cfg, const std::vector<std::string>& sets);

}  // namespace phasmid::config
