#pragma once
// The [sensitivity] section of a scenario config (docs/sensitivity.md): which parameters to
// differentiate by, over which run, by which method, and the optional limit-cycle analyses.
#include <string>

#include "config/config.hpp"
#include "continuation/sensitivity_job.hpp"

namespace phasmid::config {

// Reads a [sensitivity] table (keys: mode = "auto"|"steady_cycle"|"transient", cycle_tolerance,
// cycle_periods, parameters = [names], t_end_ms, output_dt_ms,
// discard_ms, method = "forward"|"fd", trajectory = bool, fd_relative_step,
// staggered = bool, floquet = bool, transient_ms, max_period_ms, prc_state = "name",
// prc_amplitude, prc_phases, prc_cycles). Unknown keys and wrong types are errors naming
// `origin` (e.g. the config file) and the line. Parameter names are checked against `model`.
sensitivity::SensitivityJob parse_sensitivity_section(const toml::table& section, const model::OdeModel& model,
                                                      const std::string& origin,
                                                      sensitivity::SensitivityJob defaults = {});

// The job of a config's [sensitivity] section, with the run defaults taken from `sim`
// ([simulation]); an Error naming the file if the section is missing.
sensitivity::SensitivityJob sensitivity_job(const Config& cfg, const model::OdeModel& model,
                                            const SimulationSettings& sim);

}  // namespace phasmid::config
