#pragma once
// The partitioned driver (solver/partitioned_simulator.hpp) as the Driver of run_loop
// (solver/run_loop.hpp). Its shared plumbing, events, outputs, triggers and roll-backs are in
// partitioned_simulator.cpp; each scheduler's advance in a file of its own.
#include <atomic>
#include <deque>
#include <vector>

#include "solver/command_schedule.hpp"
#include "solver/partitioned_parts.hpp"
#include "solver/simulator.hpp"
#include "solver/window_pool.hpp"

namespace phasmid::solver::partitioned {

// The parts as the Driver of run_loop: the part furthest behind steps next (see the header);
// parts at the next stop wait. Trigger crossings wait until every part has passed them (an
// earlier crossing in a lagging part may arm or fire a trigger first; in_stance reads other
// parts' states), then fire in time order. A command at tau is a new stop: parts already beyond
// tau go back to it (tau lies in their last step) and what they found after tau is discarded.
class Partitioned {
 public:
  Partitioned(Run& run, const model::OdeModel& model, const SolverOptions& options,
              const OutputTimes& output_times, size_t n_caller_roots, const std::vector<double>& y0,
              SolveResult& res);
  bool finished(const CommandSchedule& s) const { return !lagging(s) && s.last_stop(); }
  // One advance of the scheduler of this run: sequential (the part furthest behind, one step),
  // windowed (every part through one window) or on the grid of windows.
  double advance(CommandSchedule& s) {
    if (!run_.windowed) return advance_sequential(s);
    return on_grid_ ? advance_on_grid(s) : advance_window(s);
  }
  void handle_events(CommandSchedule& s);
  bool at_stop(const CommandSchedule& s) const { return !lagging(s); }
  // Every part restarts from its state at the stop before its next step (restart_pending), so
  // that its last step still serves the interpolation of outputs and events at the stop.
  void restart(double, const std::vector<double>&, double) {
    for (auto& ps : run_.parts) ps->restart_pending = true;
    ++res_.stats.restarts;
  }
  void record_outputs() {
    if (run_.windowed) {
      for (auto& ps : run_.parts) write_outputs(*ps, ps->t);
    } else if (stepped_) {
      write_outputs(*stepped_, stepped_->t);
    }
    if (options_.output_sink) flush_outputs(false);
  }
  // The caller's events in time order, each with the full right-hand side at its state; the
  // parts' counters.
  void finish(const std::vector<double>& p);

 private:
  // Sequential runs (partitioned_sequential.cpp): one step of the part furthest behind.
  double advance_sequential(CommandSchedule& s);
  PartSolver* lagging(const CommandSchedule& s) const;
  // The time of the part furthest behind: every part has reached it.
  double earliest_time() const;
  // One step of ps towards the next stop (restarting it first if a command asked for it); its
  // flag, with tret the time it returned and ps.t the time reached. Touches only ps.
  int step_once(PartSolver& ps, const CommandSchedule& s, double& tret) const;
  [[noreturn]] void step_failed(const PartSolver& ps, double tret, int flag, bool too_much_work) const;
  void take_roots(PartSolver& ps, double tret);
  void add_event(PartSolver& ps, Event e);
  // Windowed runs (SolverOptions::threads >= 2) with triggers (partitioned_windowed.cpp): every
  // part behind the window's end steps to it, concurrently, reading the others' snapshots; its
  // roots are merged after the window.
  double advance_window(CommandSchedule& s);
  long step_until(PartSolver& ps, const CommandSchedule& s, double t1, std::vector<Event>& found) const;
  // Windowed runs without triggers (partitioned_grid.cpp): windows on a fixed grid, each part
  // completing them on its own, as soon as the parts it reads have completed the one before
  // (look-ahead).
  double advance_on_grid(CommandSchedule& s);
  void extend_window_ends(const CommandSchedule& s, long upto);
  void take_windows(long k0, long K);
  void work_on_grid(const CommandSchedule& s, long K);
  PartSolver* claim_part(long K);
  bool completed(long k) const;
  void run_window(PartSolver& ps, const CommandSchedule& s) const;
  void write_states(PartSolver& ps, double t, double* row) const;
  void write_outputs(PartSolver& ps, double up_to);
  // With an output sink: the row of output k and how many parts have written it.
  double* output_row(size_t k);
  size_t& parts_done(size_t k);
  void flush_outputs(bool at_end);
  void write_pending_events(PartSolver& ps);
  void feed_triggers(CommandSchedule& s);
  void add_command_time(CommandSchedule& s, double tau, size_t k);
  void roll_back(PartSolver& x, double tau);
  long total_steps() const;

  Run& run_;
  const model::OdeModel& model_;
  const SolverOptions& options_;
  const OutputTimes& output_times_;
  const size_t n_caller_roots_;
  SolveResult& res_;
  size_t first_out_ = 0;
  std::vector<size_t> parts_done_;  // parts that have written output k
  // With an output sink: the outputs from pending_base_ on that are not yet handed to it.
  struct PendingRow {
    std::vector<double> y;
    size_t parts_done = 0;
  };
  std::deque<PendingRow> pending_;
  size_t pending_base_ = 0;
  std::vector<char> discarded_;     // per entry of res.events
  std::vector<size_t> deferred_;    // res.events entries that are trigger crossings not yet fed
  PartSolver* stepped_ = nullptr;   // the part of the last advance
  WindowPool pool_;                 // windowed runs' worker threads
  std::vector<PartSolver*> todo_, claim_;  // a window's parts, in part and in claim order
  bool on_grid_ = false;        // windowed, without triggers (whose commands roll parts back)
  long window_ = 0;             // grid runs: the last window every part has completed
  // Grid runs: the ends of windows ends_base_ ... (window 0's end is the run's start); the
  // windows before the last one taken are dropped.
  std::deque<double> ends_;
  long ends_base_ = 0;
  double window_end(long j) const { return ends_[static_cast<size_t>(j - ends_base_)]; }
  long windows_defined() const { return ends_base_ + static_cast<long>(ends_.size()); }
  std::atomic<bool> failed_{false};
  int flag_ = 0;
  std::vector<int> found_;
};

}  // namespace phasmid::solver::partitioned
