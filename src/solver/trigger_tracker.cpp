#include "solver/trigger_tracker.hpp"

#include <algorithm>

namespace phasmid::solver {

bool TriggerTracker::fires(const model::CommandTrigger& tr, double t_ms, int dir, const std::vector<double>& p,
                           const double* y) {
  const double previous_ms = last_crossing_ms_;
  last_crossing_ms_ = t_ms;
  if (fired_ || dir != tr.direction || t_ms - previous_ms < tr.debounce_ms) return false;
  const double earliest_ms = tr.after_param == model::kNoTriggerParameter ? tr.after_ms : p[tr.after_param];
  if (earliest_ms >= model::kUnresolvedMs || t_ms < earliest_ms) return false;
  // in_stance: each listed leg must be in ground contact at this crossing, its state on the
  // touched-down side of its threshold. This only selects which crossing counts (it is not a
  // root itself): the event time and its derivative are the crossing's.
  if (!std::all_of(tr.in_stance.begin(), tr.in_stance.end(), [&](const model::StanceCondition& c) {
        return c.stance_side * (y[c.state] - c.level_scale * p[c.level_param]) > 0;
      }))
    return false;
  if (++count_ < tr.occurrence) return false;
  fired_ = true;
  return true;
}

}  // namespace phasmid::solver
