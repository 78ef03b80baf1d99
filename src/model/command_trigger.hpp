#pragma once
// Command times resolved during a run from events (Knops 2013, Section 3.3: gait transitions
// take place "by the time both, the hind and the front leg, enter the stance phase", the middle
// leg's levator is released "one third of the cyclic period" after the hind leg's lift-off).
// A trigger sets one or more command-time parameters (ms) to the time of the first qualifying
// threshold crossing, plus a delay; the solver then restarts there as at any fixed command time.
// Configs give them as [[triggers]] (docs/config.md, docs/walking_model.md).
#include <cstddef>
#include <string>
#include <vector>

namespace phasmid::model {

// Value of a triggered command time until its trigger fires (as the builders' "never": beyond
// any simulation, so the command is off and no breakpoint is set).
constexpr double kUnresolvedMs = 1e9;
constexpr size_t kNoTriggerParameter = static_cast<size_t>(-1);

struct CommandTrigger {
  std::string event;            // as written in the config, e.g. "front.touchdown" (for messages)
  std::vector<size_t> targets;  // command-time parameters set to event time + delay_ms
  // The event: y[state] crosses level_scale * p[level_param] in `direction` (+1 rising, -1 falling).
  size_t state = 0;
  size_t level_param = 0;
  double level_scale = 1.0;     // e.g. pi/180: a threshold parameter in deg on an angle state in rad
  int direction = 0;
  // Earliest time of a qualifying event: after_ms, or the value of parameter after_param
  // (which may itself be triggered; the trigger is not armed before that one fired).
  double after_ms = 0.0;
  size_t after_param = kNoTriggerParameter;
  double delay_ms = 0.0;
  int occurrence = 1;           // the n-th qualifying event from the earliest time on
  // A crossing less than debounce_ms after the previous crossing of the same threshold is a
  // ripple (beta around the ground-contact threshold while a motoneuron fires) and does not count.
  double debounce_ms = 40.0;
};

}  // namespace phasmid::model
