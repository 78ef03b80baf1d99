#pragma once
// The scenario of the trigger tests (tests/solver/test_command_triggers.cpp,
// tests/sensitivity/test_trigger_sensitivity.cpp): a middle leg with the direction switch and
// rate motoneurons that steps backward from the first touch-down after `after_ms` and forward
// again `delay_ms` after the next lift-off (a chain: the second trigger is armed by the first).
#include <string>

namespace phasmid::test {

inline std::string middle_leg_trigger_config(double after_ms, double delay_ms) {
  return R"(
[model]
type = "leg"
leg = "middle"
direction_switch = true
motoneuron = "rate"

[[triggers]]
set = "middle.command.backward_ms"
event = "middle.touchdown"
after_ms = )" + std::to_string(after_ms) + R"(

[[triggers]]
set = "middle.command.forward_ms"
event = "middle.liftoff"
after = "middle.command.backward_ms"
delay_ms = )" + std::to_string(delay_ms) + "\n";
}

}  // namespace phasmid::test
