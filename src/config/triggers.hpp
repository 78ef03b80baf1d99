#pragma once
// [[triggers]] of a scenario config: command times resolved from touch-downs and lift-offs
// during the run (model::CommandTrigger; syntax in docs/config.md, use in docs/walking_model.md,
// "Gait transitions").
#include <string>
#include <vector>

#include "config/config.hpp"

namespace phasmid::config {

// Parses [[triggers]] and installs them on the model (OdeModel::set_triggers). `fixed`: the
// parameters set in [parameters] (an error if a trigger also sets one); `overrides`: parameters
// given with --set, whose fixed value replaces the trigger for that parameter. Errors are one
// line naming file:line and the key.
void apply_triggers(const Config& cfg, model::OdeModel& m, const std::vector<std::string>& fixed,
                    const std::vector<std::string>& overrides);

}  // namespace phasmid::config
