#include "solver/partitioned_simulator.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "common/error.hpp"
#include "solver/command_schedule.hpp"
#include "solver/output_sink.hpp"
#include "solver/partitioned_driver.hpp"
#include "solver/run_loop.hpp"

namespace phasmid::solver {
namespace partitioned {

Partitioned::Partitioned(Run& run, const model::OdeModel& model, const SolverOptions& options,
                         const OutputTimes& output_times, size_t n_caller_roots,
                         const std::vector<double>& y0, SolveResult& res)
    : run_(run), model_(model), options_(options), output_times_(output_times), n_caller_roots_(n_caller_roots),
      res_(res), pool_(run.windowed ? options.threads : 1) {
  on_grid_ = run.windowed && model.triggers().empty();
  if (on_grid_) {
    ends_.assign(1, 0.0);
    for (auto& ps : run.parts) {
      ps->windows.resize(static_cast<size_t>(kGridBatch + kWindowLookAhead) + 2);
      ps->take_snapshot(kWindowOrder, ps->windows[0].poly);
    }
  }
  const size_t n = model.num_states(), n_out = output_times.size();
  res.n_states = n;
  if (options.output_sink) {
    while (first_out_ < n_out && output_times[first_out_] <= 0.0) {
      options.output_sink->record(output_times[first_out_], y0.data(), n);
      res.t.assign(1, output_times[first_out_++]);
    }
    pending_base_ = first_out_;
  } else {
    parts_done_.assign(n_out, 0);
    res.t = output_times.to_vector();
    res.y.assign(n_out * n, NAN);
    res.steps_at_output.assign(n_out, 0);
    while (first_out_ < n_out && output_times[first_out_] <= 0.0) {
      std::copy(y0.begin(), y0.end(), res.y.begin() + static_cast<long>(first_out_ * n));
      ++first_out_;
    }
  }
  for (auto& ps : run.parts) ps->next_out = first_out_;
}

int Partitioned::step_once(PartSolver& ps, const CommandSchedule& s, double& tret) const {
  if (ps.restart_pending) {
    ps.session->restart(ps.t);
    ps.session->set_stop_time(s.next_stop());
    ps.restart_pending = false;
  }
  const int flag = ps.session->advance(s.next_stop(), &tret, CV_ONE_STEP);
  // CV_ONE_STEP never reports CV_TOO_MUCH_WORK: the same limit per output interval here.
  const bool too_much_work = ++ps.steps_since_output > options_.max_steps;
  if (flag < 0 || too_much_work) step_failed(ps, tret, flag, too_much_work);
  ps.t = flag == CV_TSTOP_RETURN ? s.next_stop() : ps.session->current_time();
  return flag;
}

void Partitioned::step_failed(const PartSolver& ps, double tret, int flag, bool too_much_work) const {
  std::ostringstream os;
  os << ps.session->package() << " failed at t = " << tret << " ms in part " << ps.name << ": "
     << (too_much_work ? "CV_TOO_MUCH_WORK" : ps.session->flag_name(flag)) << " " << failure_advice(options_, true);
  throw SolverError(os.str());
}

// Event e of part ps (its own states filled in) into res.events, the trigger crossings to
// feed, and the other parts' states at it: now for the parts past it (its time lies in their
// last step, sequential runs: each part's last step began at or before the lagging part's time;
// or in their history, windowed runs), the others when they get there.
void Partitioned::add_event(PartSolver& ps, Event e) {
  res_.events.push_back(std::move(e));
  discarded_.push_back(0);
  const size_t id = res_.events.size() - 1;
  const double te = res_.events[id].t;
  if (res_.events[id].root >= n_caller_roots_) deferred_.push_back(id);
  for (auto& other : run_.parts) {
    if (other.get() == &ps) continue;
    if (other->t >= te) write_states(*other, te, res_.events[id].y.data());
    else other->pending_events.push_back(id);
  }
}

double Partitioned::earliest_time() const {
  double t = INFINITY;
  for (auto& ps : run_.parts) t = std::min(t, ps->t);
  return t;
}

void Partitioned::handle_events(CommandSchedule& s) {
  if (run_.windowed) {
    for (auto& ps : run_.parts) write_pending_events(*ps);
  } else {
    write_pending_events(*stepped_);
  }
  if (!deferred_.empty()) feed_triggers(s);
}

// Writes part `ps`'s states at time t (within its last step) into the full-size state `row`.
void Partitioned::write_states(PartSolver& ps, double t, double* row) const {
  if (run_.windowed) {
    if (!ps.history.at(t, ps.states, row))
      throw SolverError("internal: part " + ps.name + " has no step covering t = " + std::to_string(t) +
                        " ms; set solver option 'threads' to 1");
    return;
  }
  N_Vector tmp = ps.session->work();
  if (ps.session->dky(t, 0, tmp) < 0) {  // the scheduling guarantees t is in the last step
    const double tn = ps.session->current_time(), hu = ps.session->last_step();
    std::ostringstream os;
    os << "internal: part " << ps.name << " cannot interpolate at t = " << t << " ms (last step " << tn - hu
       << " .. " << tn << " ms); set solver option 'partitioning' to off";
    throw SolverError(os.str());
  }
  for (size_t i = 0; i < ps.states.size(); ++i) row[ps.states[i]] = NV_Ith_S(tmp, i);
}

void Partitioned::write_outputs(PartSolver& ps, double up_to) {
  const size_t n = model_.num_states();
  while (ps.next_out < output_times_.size() && output_times_[ps.next_out] <= up_to) {
    const size_t k = ps.next_out++;
    ps.steps_since_output = 0;
    write_states(ps, output_times_[k], options_.output_sink ? output_row(k) : &res_.y[k * n]);
    if (++parts_done(k) == run_.parts.size() && !options_.output_sink) res_.steps_at_output[k] = total_steps();
  }
}

double* Partitioned::output_row(size_t k) {
  if (k < pending_base_) throw Error("internal: partitioned run rewrote an output already handed on");
  while (pending_base_ + pending_.size() <= k) pending_.push_back({std::vector<double>(model_.num_states(), NAN), 0});
  return pending_[k - pending_base_].y.data();
}

size_t& Partitioned::parts_done(size_t k) {
  if (!options_.output_sink) return parts_done_[k];
  output_row(k);
  return pending_[k - pending_base_].parts_done;
}

// Hands the outputs every part has written to the sink, in order (they complete in order: each
// part writes its outputs in order). Before the end only those no roll back can reach: a
// trigger crossing not yet fed may put a command at its time and roll back the outputs after it.
// (The part that passes a crossing last has not yet written the outputs after it when the
// crossing is fed, so those are never complete then; the bound keeps it so, and output_row
// refuses to rewrite an output handed on.)
void Partitioned::flush_outputs(bool at_end) {
  double safe_until = INFINITY;
  if (!at_end)
    for (size_t id : deferred_) safe_until = std::min(safe_until, res_.events[id].t);
  while (!pending_.empty() && pending_.front().parts_done == run_.parts.size() &&
         output_times_[pending_base_] <= safe_until) {
    options_.output_sink->record(output_times_[pending_base_], pending_.front().y.data(), model_.num_states());
    res_.t.assign(1, output_times_[pending_base_++]);
    pending_.pop_front();
  }
  if (at_end && (!pending_.empty() || pending_base_ != output_times_.size()))
    throw Error("internal: partitioned run ended with outputs not written");
}

void Partitioned::write_pending_events(PartSolver& ps) {
  for (size_t i = 0; i < ps.pending_events.size();) {
    const size_t id = ps.pending_events[i];
    if (res_.events[id].t <= ps.t) {
      write_states(ps, res_.events[id].t, res_.events[id].y.data());
      ps.pending_events.erase(ps.pending_events.begin() + static_cast<long>(i));
    } else {
      ++i;
    }
  }
}

void Partitioned::feed_triggers(CommandSchedule& s) {
  const double t_min = earliest_time();
  for (;;) {
    auto next = std::min_element(deferred_.begin(), deferred_.end(),
                                 [&](size_t a, size_t b) { return res_.events[a].t < res_.events[b].t; });
    if (next == deferred_.end() || res_.events[*next].t > t_min) return;
    const size_t id = *next;
    deferred_.erase(next);
    const Event& e = res_.events[id];
    const size_t k = e.root - n_caller_roots_;
    if (!s.fire(k, e.t, e.direction, e.y.data(), res_.commands)) continue;
    const double tau = e.t + s.triggers()[k].delay_ms;
    if (tau < s.t_end()) add_command_time(s, tau, k);
  }
}

void Partitioned::add_command_time(CommandSchedule& s, double tau, size_t k) {
  // A later stop than the next one: every part is before it.
  if (s.add_command_time(tau, {}, k) != CommandSchedule::Added::Next) return;
  for (auto& x : run_.parts) {
    if (x->t > tau) roll_back(*x, tau);
    else if (x->t < tau) x->session->set_stop_time(tau);
  }
  for (size_t id = 0; id < res_.events.size(); ++id)
    if (res_.events[id].t > tau) discarded_[id] = 1;
  auto is_discarded = [&](size_t id) { return discarded_[id] != 0; };
  deferred_.erase(std::remove_if(deferred_.begin(), deferred_.end(), is_discarded), deferred_.end());
  for (auto& x : run_.parts)
    x->pending_events.erase(std::remove_if(x->pending_events.begin(), x->pending_events.end(), is_discarded),
                            x->pending_events.end());
}

// Part x back to tau (within its last step): its outputs up to tau first (they interpolate its
// last step), then a restart from its interpolated state at tau.
void Partitioned::roll_back(PartSolver& x, double tau) {
  x.flush_polynomial();  // the others read the rolled-back step until x steps again
  write_outputs(x, tau);
  write_states(x, tau, x.yfull.data());
  for (size_t i = 0; i < x.states.size(); ++i) NV_Ith_S(x.session->y(), i) = x.yfull[x.states[i]];
  x.session->restart(tau);
  x.restart_pending = false;
  x.t = tau;
  x.history.drop_from(tau);
  while (x.next_out > first_out_ && output_times_[x.next_out - 1] > tau) --parts_done(--x.next_out);
}

long Partitioned::total_steps() const {  // grid runs: not those of windows still ahead
  long s = 0;
  for (auto& ps : run_.parts) {
    s += ps->session->total_steps();
    if (!on_grid_) continue;
    for (long j = window_ + 1; j <= ps->last_window.load(); ++j) s -= ps->windows[static_cast<size_t>(j) % ps->windows.size()].steps;
  }
  return s;
}

void Partitioned::finish(const std::vector<double>& p) {
  const size_t n = model_.num_states();
  if (options_.output_sink) flush_outputs(true);
  std::vector<Event> kept;
  for (size_t id = 0; id < res_.events.size(); ++id)
    if (!discarded_[id] && res_.events[id].root < n_caller_roots_) kept.push_back(std::move(res_.events[id]));
  res_.events = std::move(kept);
  std::stable_sort(res_.events.begin(), res_.events.end(), [](const Event& a, const Event& b) { return a.t < b.t; });
  for (Event& e : res_.events) {
    e.ydot.assign(n, 0.0);
    model_.rhs(e.t, e.y.data(), p.data(), e.ydot.data());
  }
  for (auto& ps : run_.parts) add_counters(res_.stats, ps->session->stats());
  res_.stats.integrators = static_cast<long>(run_.parts.size());
}

}  // namespace partitioned

using partitioned::Partitioned;
using partitioned::Run;

SolveResult run_partitioned(const model::OdeModel& model, const model::ModelPartition& P, const SolverOptions& options,
                            const std::vector<double>& p_given, const OutputTimes& output_times,
                            const std::vector<RootSpec>& caller_roots) {
  const SolveTimer timer;
  CommandSchedule schedule(model, p_given, output_times.back(), {});
  const std::vector<RootSpec> roots = schedule.roots(caller_roots);
  const std::vector<double> y0 = model.initial_state(schedule.p());

  // Declared before the parts: destroyed after them. Windowed runs: one per part, so that no
  // two threads share one.
  const bool windowed = options.threads >= 2;
  std::vector<std::unique_ptr<SundialsContext>> contexts(windowed ? P.size() : 1);
  for (auto& c : contexts) c = std::make_unique<SundialsContext>();
  Run run;
  run.windowed = windowed;
  run.p = &schedule.p();
  run.roots = &roots;
  schedule.parameters().mirror(run.pK);
  partitioned::build_parts(run, schedule.parameters(), model, P, roots, options);
  partitioned::start_sessions(run, model, contexts, options, y0, schedule.next_stop());

  SolveResult res;
  Partitioned driver(run, model, options, output_times, caller_roots.size(), y0, res);
  ProgressLine progress(options, schedule.t_end(), run.parts.size());
  run_loop(driver, schedule, progress);
  driver.finish(schedule.p());
  timer.stop(res.stats);
  return res;
}

}  // namespace phasmid::solver
