#include "solver/trigger_tracker.hpp"

namespace phasmid::solver {

bool TriggerTracker::fires(const model::CommandTrigger& tr, double t_ms, int dir, const std::vector<double>& p,
                           const double* y) {
  (void)y;
  const double previous_ms = last_crossing_ms_;
  last_crossing_ms_ = t_ms;
  if (fired_ || dir != tr.direction || t_ms - previous_ms < tr.debounce_ms) return false;
  const double earliest_ms = tr.after_param == model::kNoTriggerParameter ? tr.after_ms : p[tr.after_param];
  if (earliest_ms >= model::kUnresolvedMs || t_ms < earliest_ms) return false;
  if (++count_ < tr.occurrence) return false;
  fired_ = true;
  return true;
}

}  // namespace phasmid::solver
