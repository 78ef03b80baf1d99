#pragma once
// The [fit] section of a cruse1980 config (docs/cruse1980.md, "Fitting the Fig. 3 switch
// curves"): the keys every fit shares (config/fit_section.hpp) plus start_positions, cycles and
// [[fit.feature]] targets with a period_ms, read into a FitSpec whose `kind` is a
// cruse::CruseFitSpec. The cruse1980 scenario's make_fit builds the problem from it.
#include "config/config.hpp"
#include "fit/fit_spec.hpp"
#include "model/parameters.hpp"

namespace phasmid::config {

// `base` holds the scenario's parameters (after [parameters] and --set): the nominal values of
// the estimated ones. Throws Error (one line, naming file:line) on bad input.
fit::FitSpec parse_cruse_fit(const Config& cfg, const model::ParameterSet& base, const fit::FitOverrides& overrides);

}  // namespace phasmid::config
