#pragma once
// A command trigger on y[state] rising through p[level_param], setting p[target] to the
// crossing time + delay_ms: the trigger of the small test models of the solver and
// sensitivity tests.
#include <string>

#include "model/command_trigger.hpp"

namespace phasmid::test {

inline model::CommandTrigger rising_trigger(std::string event, size_t target, size_t state, size_t level_param,
                                            double delay_ms) {
  model::CommandTrigger tr;
  tr.event = std::move(event);
  tr.targets = {target};
  tr.state = state;
  tr.level_param = level_param;
  tr.direction = +1;
  tr.delay_ms = delay_ms;
  return tr;
}

}  // namespace phasmid::test
