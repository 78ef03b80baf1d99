// The windowed scheduler of the partitioned driver with triggers (SolverOptions::threads >= 2,
// a model with [[triggers]]): every part behind the window's end steps to it concurrently,
// one window at a time, since a triggered command may send parts back.
#include "solver/partitioned_driver.hpp"

#include <algorithm>
#include <exception>


namespace phasmid::solver::partitioned {

double Partitioned::advance_window(CommandSchedule& s) {
  double t_keep = earliest_time();
  const double t1 = std::min(t_keep + options_.window_ms, s.next_stop());
  for (size_t id : deferred_) t_keep = std::min(t_keep, res_.events[id].t);
  todo_.clear();
  for (auto& ps : run_.parts) {
    for (size_t q : ps->owners) run_.parts[q]->take_snapshot(kWindowOrder, ps->in_snap[q]);
    // Steps ending before t_keep are never read again (outputs, events and roll-backs come later).
    ps->history.drop_before(t_keep);
    if (ps->t < t1) todo_.push_back(ps.get());
  }
  // Claimed longest first by the previous window's steps (LPT scheduling): the short tasks come
  // last, where a thread would otherwise wait for the other's long one. The numbers do not
  // depend on the order; the events are merged in part order below.
  claim_ = todo_;
  std::stable_sort(claim_.begin(), claim_.end(),
                   [](const PartSolver* a, const PartSolver* b) { return a->window_steps > b->window_steps; });
  pool_.run(static_cast<int>(claim_.size()), [&](int i) {
    PartSolver& ps = *claim_[i];
    try {
      ps.window_steps = step_until(ps, s, t1, ps.found_in_window);
      ps.update_polynomial();  // what the others read in the next window
    } catch (...) {
      ps.failure = std::current_exception();
    }
  });
  for (PartSolver* ps : todo_)
    if (ps->failure) std::rethrow_exception(ps->failure);
  for (PartSolver* ps : todo_) {
    for (Event& e : ps->found_in_window) add_event(*ps, std::move(e));
    ps->found_in_window.clear();
  }
  return earliest_time();
}

// One part on the calling thread until it reaches t1 (or its stop), its roots into `found`; the
// number of steps. Touches only ps and its session.
long Partitioned::step_until(PartSolver& ps, const CommandSchedule& s, double t1, std::vector<Event>& found) const {
  const size_t n = model_.num_states();
  long steps = 0;
  while (ps.t < t1) {
    double tret = ps.t;
    const bool continues = !ps.restart_pending && ps.history.continues_at(ps.t);
    const int flag = step_once(ps, s, tret);
    step_roots(ps, flag, tret, n, ps.found, [&](Event e) { found.push_back(std::move(e)); });
    ps.record_step(continues);
    ++steps;
  }
  return steps;
}

}  // namespace phasmid::solver::partitioned
