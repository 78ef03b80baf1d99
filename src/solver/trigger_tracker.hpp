#pragma once
// Which threshold crossing fires a [[triggers]] entry (model::CommandTrigger): the crossings of
// its threshold are fed in time order; the first one in the trigger's direction, not within
// debounce_ms of the previous crossing, at or after the earliest time, with the in_stance legs
// in stance, and the occurrence-th such, fires it. One per trigger in the CommandSchedule
// (solver/command_schedule.hpp), which both drivers use.
#include <cmath>
#include <vector>

#include "model/command_trigger.hpp"

namespace phasmid::solver {

class TriggerTracker {
 public:
  // A crossing at t_ms in direction dir (+1 rising, -1 falling), with p the parameter vector
  // as resolved so far (earliest times may be other triggers' command times) and y the full
  // state at the crossing. True if this crossing fires the trigger (once).
  bool fires(const model::CommandTrigger& tr, double t_ms, int dir, const std::vector<double>& p, const double* y);
  bool fired() const { return fired_; }

 private:
  bool fired_ = false;
  int count_ = 0;
  double last_crossing_ms_ = -INFINITY;
};

}  // namespace phasmid::solver
