#pragma once
// Command times resolved during a run from events (Knops 2013, Section 3.3: gait transitions
// take place "by the time both, the hind and the front leg, enter the stance phase", the middle
// leg's levator is released "one third of the cyclic period" after the hind leg's lift-off).
// A trigger sets one or more command-time parameters (ms) to the time of the first qualifying
// threshold crossing, plus a delay; the solver then restarts there as at any fixed command time.
// A crossing qualifies only if the legs named in `in_stance` are in stance at that moment.
// Configs give them as [[triggers]] (docs/config.md, docs/walking_model.md).
#include <cstddef>
#include <string>
#include <vector>

namespace phasmid::model {

// Value of a triggered command time until its trigger fires (as the builders' "never": beyond
// any simulation, so the command is off and no breakpoint is set).
constexpr double kUnresolvedMs = 1e9;
constexpr size_t kNoTriggerParameter = static_cast<size_t>(-1);

// A leg that must be in stance (ground contact) at the event for it to count: its state
// y[state] is on the touched-down side of level_scale * p[level_param], i.e.
// stance_side * (y[state] - level) > 0, stance_side the direction of its touch-down crossing
// (-1: beta below <leg>.coupling.beta_thr_pr, as the touch-down events and the footfall pattern).
struct StanceCondition {
  std::string leg;  // as written in the config (for messages)
  size_t state = 0;
  size_t level_param = 0;
  double level_scale = 1.0;
  int stance_side = -1;
};

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
  // Legs in stance at the event (config key in_stance); empty: every crossing qualifies. Only
  // selects which crossing counts: the event time and its derivatives are those of the crossing.
  std::vector<StanceCondition> in_stance;
};

}  // namespace phasmid::model
