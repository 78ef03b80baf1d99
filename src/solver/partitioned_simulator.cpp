#include "solver/partitioned_simulator.hpp"

#include <cvodes/cvodes.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <deque>
#include <exception>
#include <memory>
#include <sstream>
#include <thread>

#include "common/error.hpp"
#include "solver/command_schedule.hpp"
#include "solver/cvodes_session.hpp"
#include "solver/erk_session.hpp"
#include "solver/output_sink.hpp"
#include "solver/run_loop.hpp"
#include "solver/step_history.hpp"
#include "solver/window_pool.hpp"

namespace phasmid::solver {
using model::JetK;
using model::kJacobianChunk;

namespace {

constexpr int kMaxOrder = 12;  // Adams' maximum; BDF stops at 5
constexpr long kGridBatch = 8;  // windows per call of Partitioned::advance_on_grid

struct Run;

// Taylor coefficients c[d * stride + e] of entry e at a point, evaluated dt after it.
double horner(const std::vector<double>& c, size_t stride, size_t e, int order, double dt) {
  double v = c[static_cast<size_t>(order) * stride + e];
  for (int d = order - 1; d >= 0; --d) v = v * dt + c[static_cast<size_t>(d) * stride + e];
  return v;
}

// A part's polynomial of its exported states as another part reads it during a window: taken
// at the window's start, extrapolated at most to extrapolation_order beyond its last step.
struct Snapshot {
  double t_poly = 0.0;
  int order = 0, extrapolation_order = 0;
  std::vector<double> coef;  // as PartSolver::coef, orders 0..order

  double value(size_t n_exports, size_t e, double at) const {
    const double dt = at - t_poly;
    return horner(coef, n_exports, e, dt > 0.0 ? extrapolation_order : order, dt);
  }
};

// One part's integrator and the polynomial through which the other parts read its angles.
struct PartSolver {
  const Run* run = nullptr;
  std::string name;
  std::vector<size_t> states;                         // global indices of its own states
  std::vector<size_t> inputs;                         // global indices of states it reads from others
  std::vector<std::pair<size_t, size_t>> input_from;  // per input: (part, index into that part's exports)
  std::vector<size_t> exports;                        // local indices of its states others read
  bool stiff = false;  // ModelPartition::stiff: BDF at stiff_part_tol in an explicit run
  std::unique_ptr<model::OdeModelPart> eq;
  std::unique_ptr<IntegratorSession> session;

  std::vector<double> yfull, ffull;  // full-size state and derivative for the part's equations
  std::vector<double> u;             // its inputs, packed (OdeModelPart::rhs_packed)
  std::vector<JetK> yK, fK;

  // Interpolating polynomial of the last step, as Taylor coefficients at t_poly:
  // coef[d * exports.size() + e] = (d^d y_e / dt^d)(t_poly) / d!.
  double t_poly = 0.0;
  int order = 0;
  std::vector<double> coef;

  double t = 0.0;        // time reached (CVODES' internal tn)
  bool restart_pending = false;  // at a stop: restarts from there before its next step
  // Sequential runs: the polynomial is taken from the session only when another part may read
  // it (flush_polynomial): a part that steps again first never had its last one read.
  bool polynomial_stale = false;
  size_t next_out = 0;   // first output time not yet written
  long steps_since_output = 0;  // against SolverOptions::max_steps (per output interval)
  std::vector<size_t> roots;          // global root indices watched by this part
  std::vector<size_t> root_state;     // their local state indices
  std::vector<size_t> pending_events; // events whose state this part has not yet passed

  // Windowed runs (SolverOptions::threads >= 2): per part, what this part reads of it during
  // its present window (its owners only); its steps since the earliest time still read, the
  // roots found in the window (own states only) and a failure to rethrow after it.
  std::vector<Snapshot> in_snap;
  StepHistory history;
  std::vector<double> y0, f0;  // record_step's buffers
  std::vector<Event> found_in_window;
  std::vector<int> found;   // root_info's buffer
  long window_steps = 0;    // steps in its last window: the forecast of its next one's cost
  std::exception_ptr failure;

  // Windowed runs on the grid of windows (Partitioned::advance_on_grid): window j of this part
  // as the run takes it when every part has completed j, kept in a ring of windows[j % size]
  // so that the part can complete later windows first.
  struct Window {
    double t = 0.0;  // where it stood at the window's end: its first step end at or past it
    Snapshot poly;   // what its readers read in the next window
    std::vector<Event> found;
    long steps = 0;
  };
  std::vector<Window> windows;
  std::atomic<long> last_window{0};  // the last window it completed (release: windows[] written)
  std::atomic<bool> busy{false};     // a thread is stepping it
  double t_real = 0.0;               // where its integrator stands; t is where the run has taken it
  std::vector<size_t> owners;        // the parts it reads

  double export_value(size_t e, double at) const;

  void flush_polynomial() {
    if (polynomial_stale) update_polynomial();
    polynomial_stale = false;
  }

  void update_polynomial() {
    if (exports.empty()) return;
    const int q = session->interpolation_degree();
    const double tn = session->current_time();
    const size_t ne = exports.size();
    double factorial = 1.0;
    for (int d = 0; d <= q; ++d) {
      if (d > 0) factorial *= d;
      check_cvodes(session->dky(tn, d, session->work()), "the last step's interpolant (GetDky)");
      for (size_t e = 0; e < ne; ++e)
        coef[static_cast<size_t>(d) * ne + e] = NV_Ith_S(session->work(), exports[e]) / factorial;
    }
    order = q;
    t_poly = tn;
  }

  // Windowed runs: the last step into the history, once its roots have been taken (the
  // session's y() is then the state at the step's end): the derivative at its end, and the
  // values at its start unless the previous step ended there without a restart.
  void record_step(bool continues) {
    const double tn = session->current_time(), t0 = tn - session->last_step();
    if (!continues) {
      take_dky(t0, 0, y0);
      take_dky(t0, 1, f0);
    }
    check_cvodes(session->dky(tn, 1, session->work()), "the last step's interpolant (GetDky)");
    history.record(t0, tn, continues ? nullptr : y0.data(), continues ? nullptr : f0.data(),
                   N_VGetArrayPointer(session->y()), N_VGetArrayPointer(session->work()));
  }

  void take_dky(double t, int k, std::vector<double>& out) {
    check_cvodes(session->dky(t, k, session->work()), "the last step's interpolant (GetDky)");
    const double* w = N_VGetArrayPointer(session->work());
    out.assign(w, w + states.size());
  }

  // What the others read in the coming window: the present polynomial.
  void take_snapshot(int extrapolation_order, Snapshot& snap) const {
    snap.t_poly = t_poly;
    snap.order = order;
    snap.extrapolation_order = std::min(order, extrapolation_order);
    snap.coef.assign(coef.begin(), coef.begin() + static_cast<long>(static_cast<size_t>(order + 1) * exports.size()));
  }
};

struct Run {
  std::vector<std::unique_ptr<PartSolver>> parts;
  const std::vector<double>* p = nullptr;
  std::vector<JetK> pK;
  const std::vector<RootSpec>* roots = nullptr;
  bool windowed = false;  // parts read each other's snapshots (SolverOptions::threads >= 2)
};

double PartSolver::export_value(size_t e, double at) const {
  return horner(coef, exports.size(), e, order, at - t_poly);
}

// Whether every x[i] is finite: its exponent bits are not all ones. Integer tests are exact in
// any order, so the loop vectorises and has no chain of dependent additions (a sum of x - x,
// the previous form, cost one floating-point add latency per entry).
bool all_finite(const double* x, size_t n) {
  constexpr uint64_t kExponent = 0x7ff0000000000000ull;
  uint64_t bad = 0;
  for (size_t i = 0; i < n; ++i) {
    uint64_t bits;
    std::memcpy(&bits, x + i, sizeof bits);
    bad |= static_cast<uint64_t>((bits & kExponent) == kExponent);
  }
  return bad == 0;
}

// Input i of the part at time t from its owner's polynomial (windowed runs: from the snapshot
// of the part's present window).
double input_value(const PartSolver& ps, size_t i, double t) {
  const auto& [owner, e] = ps.input_from[i];
  const PartSolver& o = *ps.run->parts[owner];
  return ps.run->windowed ? ps.in_snap[owner].value(o.exports.size(), e, t) : o.export_value(e, t);
}

// The part's inputs at time t, written into a full-size vector at their indices.
template <class Scalar>
void fill_inputs(const PartSolver& ps, double t, std::vector<Scalar>& full) {
  for (size_t i = 0; i < ps.inputs.size(); ++i) full[ps.inputs[i]] = Scalar(input_value(ps, i, t));
}

// The part's inputs at time t, packed (u[i] = input i). Sequential runs read each owner's
// polynomial here, inlined, so that the inputs' Horner chains overlap rather than wait on one
// another through a call per input.
void gather_inputs(const PartSolver& ps, double t, double* u) {
  const size_t m = ps.input_from.size();
  if (ps.run->windowed) {
    for (size_t i = 0; i < m; ++i) u[i] = input_value(ps, i, t);
    return;
  }
  for (size_t i = 0; i < m; ++i) {
    const auto& [owner, e] = ps.input_from[i];
    u[i] = ps.run->parts[owner]->export_value(e, t);
  }
}

int part_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* ud) {
  auto* ps = static_cast<PartSolver*>(ud);
  const double* yv = N_VGetArrayPointer(y);
  double* out = N_VGetArrayPointer(ydot);
  const size_t n = ps->states.size();
  if (ps->eq->packed()) {  // a compiled part reads its states and inputs where they are
    gather_inputs(*ps, t, ps->u.data());
    ps->eq->rhs_packed(t, yv, ps->u.data(), ps->run->p->data(), out);
  } else {
    fill_inputs(*ps, t, ps->yfull);
    for (size_t i = 0; i < n; ++i) ps->yfull[ps->states[i]] = yv[i];
    ps->eq->rhs(t, ps->yfull.data(), ps->run->p->data(), ps->ffull.data());
    for (size_t i = 0; i < n; ++i) out[i] = ps->ffull[ps->states[i]];
  }
  return all_finite(out, n) ? 0 : 1;  // recoverable: the integrator retries a smaller step
}

// Dense Jacobian of the part's own equations by forward-mode AD (inputs held fixed).
int part_jac(sunrealtype t, N_Vector y, N_Vector, SUNMatrix Jm, void* ud, N_Vector, N_Vector, N_Vector) {
  auto* ps = static_cast<PartSolver*>(ud);
  fill_inputs(*ps, t, ps->yK);
  const double* yv = N_VGetArrayPointer(y);
  const size_t n = ps->states.size();
  double* J = SUNDenseMatrix_Data(Jm);
  for (size_t c0 = 0; c0 < n; c0 += kJacobianChunk) {
    for (size_t i = 0; i < n; ++i) {
      JetK& v = ps->yK[ps->states[i]];
      v = JetK(yv[i]);
      if (i >= c0 && i < c0 + kJacobianChunk) v.v[i - c0] = 1.0;
    }
    ps->eq->rhs(t, ps->yK.data(), ps->run->pK.data(), ps->fK.data());
    for (size_t k = 0; k < kJacobianChunk && c0 + k < n; ++k)
      for (size_t i = 0; i < n; ++i) J[(c0 + k) * n + i] = ps->fK[ps->states[i]].v[k];
  }
  return 0;
}

int part_roots(sunrealtype, N_Vector y, sunrealtype* g, void* ud) {
  auto* ps = static_cast<PartSolver*>(ud);
  for (size_t r = 0; r < ps->roots.size(); ++r)
    g[r] = NV_Ith_S(y, ps->root_state[r]) - (*ps->run->roots)[ps->roots[r]].level;
  return 0;
}

// The parts of P with their equations, who reads whose exports, and which roots each watches.
void build_parts(Run& run, const model::OdeModel& model, const model::ModelPartition& P,
                 const std::vector<RootSpec>& roots, const SolverOptions& options) {
  const size_t n = model.num_states();
  std::vector<size_t> part_of(n), local_of(n);
  for (size_t k = 0; k < P.size(); ++k)
    for (size_t i = 0; i < P.states[k].size(); ++i) {
      part_of[P.states[k][i]] = k;
      local_of[P.states[k][i]] = i;
    }
  for (size_t k = 0; k < P.size(); ++k) {
    auto ps = std::make_unique<PartSolver>();
    ps->run = &run;
    ps->name = P.names[k];
    ps->states = P.states[k];
    ps->history = StepHistory(ps->states.size());
    ps->inputs = P.inputs[k];
    ps->stiff = P.is_stiff(k);
    ps->eq = model.make_part(P, k);
    if (!ps->eq) throw Error("internal: model " + model.kind() + " has no equations for part " + ps->name);
    ps->eq->bind(run.p->data());
    compile_if_asked(ps->eq.get(), options);
    ps->yfull.assign(n, 0.0);
    ps->ffull.assign(n, 0.0);
    ps->u.assign(ps->inputs.size(), 0.0);
    ps->yK.assign(n, JetK(0.0));
    ps->fK.assign(n, JetK(0.0));
    run.parts.push_back(std::move(ps));
  }
  for (auto& ps : run.parts)
    for (size_t g : ps->inputs) {
      PartSolver& owner = *run.parts[part_of[g]];
      const size_t local = local_of[g];
      auto at = std::find(owner.exports.begin(), owner.exports.end(), local);
      if (at == owner.exports.end()) at = owner.exports.insert(owner.exports.end(), local);
      ps->input_from.emplace_back(part_of[g], static_cast<size_t>(at - owner.exports.begin()));
    }
  for (auto& ps : run.parts) {
    for (const auto& from : ps->input_from) ps->owners.push_back(from.first);
    std::sort(ps->owners.begin(), ps->owners.end());
    ps->owners.erase(std::unique(ps->owners.begin(), ps->owners.end()), ps->owners.end());
    ps->in_snap.resize(run.parts.size());
  }
  for (size_t r = 0; r < roots.size(); ++r) {
    PartSolver& ps = *run.parts[part_of.at(roots[r].state)];
    ps.roots.push_back(r);
    ps.root_state.push_back(local_of[roots[r].state]);
  }
}

// The roots of the step a part has just taken (flag CV_ROOT_RETURN at tret), each as an event
// with the part's own states, to `take`: a second call in CV_NORMAL mode to the time reached
// returns the step's remaining roots one by one and then y(t) without stepping.
template <class Take>
void step_roots(PartSolver& ps, int flag, double tret, size_t n, std::vector<int>& found, Take take) {
  while (flag == CV_ROOT_RETURN) {
    found.assign(ps.roots.size(), 0);
    ps.session->root_info(found.data());
    for (size_t r = 0; r < ps.roots.size(); ++r) {
      if (!found[r]) continue;
      Event e;
      e.t = tret;
      e.root = ps.roots[r];
      e.direction = found[r];
      e.y.assign(n, NAN);
      for (size_t i = 0; i < ps.states.size(); ++i) e.y[ps.states[i]] = NV_Ith_S(ps.session->y(), i);  // y(tret)
      take(std::move(e));
    }
    flag = ps.session->advance(ps.t, &tret, CV_NORMAL);
    if (flag < 0) check_cvodes(flag, "CVode (roots of the last step)");
  }
}

// A part's integrator settings: a stiff part (ModelPartition::stiff) of an explicit run is
// CVODES BDF at stiff_part_tol, where an explicit method's steps would be bounded by stability.
SolverOptions options_of_part(const SolverOptions& options, bool stiff) {
  if (!stiff || !is_explicit_rk(options.integrator)) return options;
  SolverOptions o = options;
  o.integrator = IntegratorKind::Bdf;
  o.rtol = o.atol = options.stiff_part_tol;
  o.atol_by_unit = options.stiff_part_atol_by_unit;
  return o;
}

// Each part's integrator from y0, integrating towards the first stop.
void start_sessions(Run& run, const model::OdeModel& model, const std::vector<std::unique_ptr<SundialsContext>>& contexts,
                    const SolverOptions& options, const std::vector<double>& y0, double first_stop) {
  for (size_t k = 0; k < run.parts.size(); ++k) {
    PartSolver& ps = *run.parts[k];
    SUNContext ctx = contexts[std::min(k, contexts.size() - 1)]->get();
    std::vector<double> own(ps.states.size());
    for (size_t i = 0; i < ps.states.size(); ++i) own[i] = y0[ps.states[i]];
    // Before its first step a part's polynomial is its initial value.
    ps.coef.assign(static_cast<size_t>(kMaxOrder + 1) * ps.exports.size(), 0.0);
    for (size_t e = 0; e < ps.exports.size(); ++e) ps.coef[e] = y0[ps.states[ps.exports[e]]];
    const SolverOptions part_options = options_of_part(options, ps.stiff);
    if (is_explicit_rk(part_options.integrator)) {
      ps.session = make_explicit_session(ctx, part_options, own.data(), own.size(), part_rhs, &ps);
    } else {
      auto cv = std::make_unique<CvodesSession>(ctx, part_options, own.data(), own.size(), part_rhs, &ps);
      // Parts are small (a joint: 20-26 states): dense LU with the compiled kernels.
      cv->set_linear_solver(LinearSystem::Dense, 0, 0, options.jacobian == JacobianKind::AutoDiff ? part_jac : nullptr);
      ps.session = std::move(cv);
    }
    if (!part_options.atol_by_unit.empty()) ps.session->set_state_atol(state_atol(model, part_options, ps.states));
    std::vector<int> dirs;
    for (size_t r : ps.roots) dirs.push_back((*run.roots)[r].direction);
    ps.session->init_roots(dirs, part_roots);
    ps.session->set_stop_time(first_stop);
  }
}

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
  double advance(CommandSchedule& s);
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
  PartSolver* lagging(const CommandSchedule& s) const;
  // The time of the part furthest behind: every part has reached it.
  double earliest_time() const;
  // One step of ps towards the next stop (restarting it first if a command asked for it); its
  // flag, with tret the time it returned and ps.t the time reached. Touches only ps.
  int step_once(PartSolver& ps, const CommandSchedule& s, double& tret) const;
  [[noreturn]] void step_failed(const PartSolver& ps, double tret, int flag, bool too_much_work) const;
  void take_roots(PartSolver& ps, double tret);
  void add_event(PartSolver& ps, Event e);
  // Windowed runs (SolverOptions::threads >= 2) with triggers: every part behind the window's
  // end steps to it, concurrently, reading the others' snapshots; its roots are merged after
  // the window.
  double advance_window(CommandSchedule& s);
  long step_until(PartSolver& ps, const CommandSchedule& s, double t1, std::vector<Event>& found) const;
  // Windowed runs without triggers: windows on a fixed grid, each part completing them on its
  // own, as soon as the parts it reads have completed the one before (look-ahead).
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
  long look_ahead_ = 0;         // grid runs: SolverOptions::window_look_ahead, at least 0
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

Partitioned::Partitioned(Run& run, const model::OdeModel& model, const SolverOptions& options,
                         const OutputTimes& output_times, size_t n_caller_roots,
                         const std::vector<double>& y0, SolveResult& res)
    : run_(run), model_(model), options_(options), output_times_(output_times), n_caller_roots_(n_caller_roots),
      res_(res), pool_(run.windowed ? options.threads : 1) {
  on_grid_ = run.windowed && model.triggers().empty();
  look_ahead_ = std::max(options.window_look_ahead, 0);
  if (on_grid_) {
    ends_.assign(1, 0.0);
    for (auto& ps : run.parts) {
      ps->windows.resize(static_cast<size_t>(kGridBatch + look_ahead_) + 2);
      ps->take_snapshot(options.window_order, ps->windows[0].poly);
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

PartSolver* Partitioned::lagging(const CommandSchedule& s) const {
  PartSolver* lag = nullptr;
  for (auto& ps : run_.parts)
    if (ps->t < s.next_stop() && (!lag || ps->t < lag->t)) lag = ps.get();
  return lag;
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

double Partitioned::advance(CommandSchedule& s) {
  if (run_.windowed) return on_grid_ ? advance_on_grid(s) : advance_window(s);
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

double Partitioned::advance_window(CommandSchedule& s) {
  double t_keep = earliest_time();
  const double t1 = std::min(t_keep + options_.window_ms, s.next_stop());
  for (size_t id : deferred_) t_keep = std::min(t_keep, res_.events[id].t);
  todo_.clear();
  for (auto& ps : run_.parts) {
    for (size_t q : ps->owners) run_.parts[q]->take_snapshot(options_.window_order, ps->in_snap[q]);
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

// The windows of every part up to K (at most kGridBatch past the last one taken, and not past
// the next stop), then their events, window by window in part order. The parts' windows are
// claimed by whichever thread is free: the window j of a part whose owners (the parts it
// reads) have completed j - 1, the earliest first; a part may go up to window_look_ahead
// windows past K while another still steps before K. A part's window j reads only its owners'
// polynomials at the end of j - 1, so the numbers do not depend on which windows were
// completed first, nor on the thread count or timing. (Several windows per call spare the
// threads a hand-over per window: the events, outputs and snapshots in between are serial.)
double Partitioned::advance_on_grid(CommandSchedule& s) {
  const long k0 = window_ + 1;
  extend_window_ends(s, k0 + kGridBatch - 1 + look_ahead_);
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
// still before it, and at most window_look_ahead past it.
PartSolver* Partitioned::claim_part(long K) {
  const bool before_K = !completed(K);
  auto next_ready = [&](const PartSolver& ps) -> long {
    const long j = ps.last_window.load(std::memory_order_acquire) + 1;
    if (j > K + (before_K ? look_ahead_ : 0) || j >= windows_defined()) return -1;
    for (size_t q : ps.owners)
      if (run_.parts[q]->last_window.load(std::memory_order_acquire) < j - 1) return -1;
    return j;
  };
  const bool ahead_first = options_.window_look_ahead_always;  // tests: the windows past K first
  PartSolver* best = nullptr;
  long best_j = 0;
  for (PartSolver* ps : claim_) {
    if (ps->busy.load(std::memory_order_relaxed)) continue;
    const long j = next_ready(*ps);
    if (j < 0) continue;
    const bool read = !ps->exports.empty(), best_read = best && !best->exports.empty();
    const bool earlier = ahead_first ? j > best_j : j < best_j;
    if (!best || earlier || (j == best_j && read > best_read)) best = ps, best_j = j;
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
    ps.take_snapshot(options_.window_order, w.poly);
  } else {
    w.poly = ps.windows[static_cast<size_t>(j - 1) % ring].poly;
  }
  w.t = ps.t_real = ps.t;
  ps.t = taken;
  ps.last_window.store(j, std::memory_order_release);
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
                        " ms; set [simulation] threads = 1");
    return;
  }
  N_Vector tmp = ps.session->work();
  if (ps.session->dky(t, 0, tmp) < 0) {  // the scheduling guarantees t is in the last step
    const double tn = ps.session->current_time(), hu = ps.session->last_step();
    std::ostringstream os;
    os << "internal: part " << ps.name << " cannot interpolate at t = " << t << " ms (last step " << tn - hu
       << " .. " << tn << " ms); set [simulation] partitioned = false";
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
    for (size_t q : s.triggers()[k].targets) run_.pK[q] = JetK(tau);
    for (auto& x : run_.parts) x->eq->bind(s.p().data());
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

}  // namespace

void check_atol_units(const model::OdeModel& model, const SolverOptions& options) {
  std::vector<std::string> units;  // in the order of their first state
  for (const model::StateInfo& s : model.states())
    if (std::find(units.begin(), units.end(), s.unit) == units.end()) units.push_back(s.unit);
  auto check = [&](const char* key, const std::vector<std::pair<std::string, double>>& by_unit) {
    for (const auto& entry : by_unit) {
      if (std::find(units.begin(), units.end(), entry.first) != units.end()) continue;
      std::string list;
      for (const std::string& u : units) list += (list.empty() ? "'" : ", '") + u + "'";
      throw Error(std::string("[simulation] ") + key + ": no state of this model has unit '" + entry.first +
                  "' (its units: " + list + ")");
    }
  };
  check("atol_by_unit", options.atol_by_unit);
  check("stiff_part_atol_by_unit", options.stiff_part_atol_by_unit);
}

// The absolute tolerance of each of `states` (SolverOptions::atol_by_unit).
std::vector<double> state_atol(const model::OdeModel& model, const SolverOptions& options,
                               const std::vector<size_t>& states) {
  std::vector<double> atol(states.size(), options.atol);
  for (size_t i = 0; i < states.size(); ++i)
    for (const auto& [unit, value] : options.atol_by_unit)
      if (model.states()[states[i]].unit == unit) atol[i] = value;
  return atol;
}

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
  for (double v : schedule.p()) run.pK.emplace_back(v);
  build_parts(run, model, P, roots, options);
  start_sessions(run, model, contexts, options, y0, schedule.next_stop());

  SolveResult res;
  Partitioned driver(run, model, options, output_times, caller_roots.size(), y0, res);
  ProgressLine progress(options, schedule.t_end(), run.parts.size());
  run_loop(driver, schedule, progress);
  driver.finish(schedule.p());
  timer.stop(res.stats);
  return res;
}

}  // namespace phasmid::solver
