// The grid scheduler of the partitioned driver (SolverOptions::threads >= 2, no triggers):
// windows on a fixed grid, which each part completes as soon as the parts it reads have
// completed the one before.
#include "solver/partitioned_driver.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <thread>

#include "common/error.hpp"

namespace phasmid::solver::partitioned {

// The windows of every part up to K (at most kGridBatch past the last one taken, and not past
// the next stop), then their events, window by window in part order. The parts' windows are
// claimed by whichever thread is free: the window j of a part whose owners (the parts it
// reads) have completed j - 1, the earliest first; a part may go up to kWindowLookAhead
// windows past K while another still steps before K. A part's window j reads only its owners'
// polynomials at the end of j - 1, so the numbers do not depend on which windows were
// completed first, nor on the thread count or timing. (Several windows per call spare the
// threads a hand-over per window: the events, outputs and snapshots in between are serial.)
double Partitioned::advance_on_grid(CommandSchedule& s) {
  const long k0 = window_ + 1;
  extend_window_ends(s, k0 + kGridBatch - 1 + kWindowLookAhead);
  const long last = windows_defined() - 1;
  if (last < k0) throw Error("internal: windowed run advanced past its stop");
  const long K = std::min(k0 + kGridBatch - 1, last);
  const double t_keep = earliest_time();
  claim_.clear();
  for (auto& ps : run_.parts) {
    ps->history.drop_before(t_keep);  // steps ending before t_keep are never read again
    claim_.push_back(ps.get());
  }
  std::stable_sort(claim_.begin(), claim_.end(),  // LPT, as in advance_window
                   [](const PartSolver* a, const PartSolver* b) { return a->window_steps > b->window_steps; });
  pool_.run(options_.threads, [&](int) { work_on_grid(s, K); });
  for (auto& ps : run_.parts)
    if (ps->failure) std::rethrow_exception(ps->failure);
  take_windows(k0, K);
  return earliest_time();
}

// Windows k0 ... K into the run, each as if every part had just completed it: the parts' times,
// then the roots in part order.
void Partitioned::take_windows(long k0, long K) {
  const size_t ring = run_.parts.front()->windows.size();
  for (long k = k0; k <= K; ++k) {
    const size_t slot = static_cast<size_t>(k) % ring;
    for (auto& ps : run_.parts) {
      ps->t = ps->windows[slot].t;
      ps->window_steps = ps->windows[slot].steps;
    }
    for (auto& ps : run_.parts) {
      for (Event& e : ps->windows[slot].found) add_event(*ps, std::move(e));
      ps->windows[slot].found.clear();
    }
  }
  window_ = K;
  while (ends_base_ < K) {  // window K's end stays: it is where window K + 1 starts
    ends_.pop_front();
    ++ends_base_;
  }
}

// Each window ends at the next multiple of window_ms or at the next stop, whichever is first;
// none is defined past the next stop until the run has passed it.
void Partitioned::extend_window_ends(const CommandSchedule& s, long upto) {
  const double w = options_.window_ms;
  while (windows_defined() <= upto && ends_.back() < s.next_stop()) {
    double m = std::floor(ends_.back() / w) + 1.0;
    if (m * w <= ends_.back()) m += 1.0;  // the division rounded up to a multiple
    ends_.push_back(std::min(m * w, s.next_stop()));
  }
}

void Partitioned::work_on_grid(const CommandSchedule& s, long K) {
  while (!failed_.load()) {
    PartSolver* ps = claim_part(K);
    if (!ps) {
      if (completed(K)) return;
      std::this_thread::yield();
      continue;
    }
    try {
      run_window(*ps, s);
    } catch (...) {
      ps->failure = std::current_exception();
      failed_ = true;
    }
    ps->busy.store(false, std::memory_order_release);
  }
}

bool Partitioned::completed(long k) const {
  for (auto& ps : run_.parts)
    if (ps->last_window.load(std::memory_order_acquire) < k) return false;
  return true;
}

// A part to step, now this thread's (busy): among those whose next window j is ready (every
// part it reads has completed j - 1), the earliest j, parts the others read first (the further
// they lead, the more of their readers' windows are ready); past K only while another part is
// still before it, and at most kWindowLookAhead past it.
PartSolver* Partitioned::claim_part(long K) {
  const bool before_K = !completed(K);
  auto next_ready = [&](const PartSolver& ps) -> long {
    const long j = ps.last_window.load(std::memory_order_acquire) + 1;
    if (j > K + (before_K ? kWindowLookAhead : 0) || j >= windows_defined()) return -1;
    for (size_t q : ps.owners)
      if (run_.parts[q]->last_window.load(std::memory_order_acquire) < j - 1) return -1;
    return j;
  };
  PartSolver* best = nullptr;
  long best_j = 0;
  for (PartSolver* ps : claim_) {
    if (ps->busy.load(std::memory_order_relaxed)) continue;
    const long j = next_ready(*ps);
    if (j < 0) continue;
    const bool read = !ps->exports.empty(), best_read = best && !best->exports.empty();
    if (!best || j < best_j || (j == best_j && read > best_read)) best = ps, best_j = j;
  }
  if (!best) return nullptr;
  bool idle = false;
  if (!best->busy.compare_exchange_strong(idle, true, std::memory_order_acquire)) return nullptr;
  if (next_ready(*best) == best_j) return best;
  best->busy.store(false, std::memory_order_release);  // another thread took that window meanwhile
  return nullptr;
}

// The next window of ps (busy: this thread's), reading its owners' polynomials at the end of
// the window before.
void Partitioned::run_window(PartSolver& ps, const CommandSchedule& s) const {
  const long j = ps.last_window.load(std::memory_order_relaxed) + 1;
  const size_t ring = ps.windows.size();
  for (size_t q : ps.owners) ps.in_snap[q] = run_.parts[q]->windows[static_cast<size_t>(j - 1) % ring].poly;
  PartSolver::Window& w = ps.windows[static_cast<size_t>(j) % ring];
  w.found.clear();
  const double taken = ps.t;  // the run's, restored below; its integrator is at t_real
  ps.t = ps.t_real;
  w.steps = step_until(ps, s, window_end(j), w.found);
  if (w.steps > 0) {
    ps.update_polynomial();
    ps.take_snapshot(kWindowOrder, w.poly);
  } else {
    w.poly = ps.windows[static_cast<size_t>(j - 1) % ring].poly;
  }
  w.t = ps.t_real = ps.t;
  ps.t = taken;
  ps.last_window.store(j, std::memory_order_release);
}

}  // namespace phasmid::solver::partitioned
