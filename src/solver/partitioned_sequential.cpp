// The sequential scheduler of the partitioned driver (SolverOptions::threads = 1): the part
// furthest behind takes the next step, so every other part's last step covers its time.
#include "solver/partitioned_driver.hpp"

#include <cmath>

#include "common/error.hpp"

namespace phasmid::solver::partitioned {

PartSolver* Partitioned::lagging(const CommandSchedule& s) const {
  PartSolver* lag = nullptr;
  for (auto& ps : run_.parts)
    if (ps->t < s.next_stop() && (!lag || ps->t < lag->t)) lag = ps.get();
  return lag;
}

double Partitioned::advance_sequential(CommandSchedule& s) {
  stepped_ = lagging(s);
  if (!stepped_) throw Error("internal: partitioned run advanced with every part at its stop");
  PartSolver& ps = *stepped_;
  for (auto& other : run_.parts)
    if (other.get() != &ps) other->flush_polynomial();  // ps's step reads them
  double tret = ps.t;
  flag_ = step_once(ps, s, tret);
  ps.polynomial_stale = true;
  take_roots(ps, tret);
  return ps.t;
}

// Every root of this step is taken now, before another part steps on (step_roots). (Another
// part's next step could otherwise leave the time of a later root of this step, where its
// state is interpolated.)
void Partitioned::take_roots(PartSolver& ps, double tret) {
  step_roots(ps, flag_, tret, model_.num_states(), found_, [&](Event e) { add_event(ps, std::move(e)); });
}

}  // namespace phasmid::solver::partitioned
