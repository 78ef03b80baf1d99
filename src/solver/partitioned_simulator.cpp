#include "solver/partitioned_simulator.hpp"

#include <cvodes/cvodes.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

#include "common/error.hpp"
#include "solver/cvodes_counters.hpp"
#include "solver/cvodes_setup.hpp"
#include "solver/matrix_kernels.hpp"
#include "solver/serial_kernels.hpp"
#include "solver/trigger_tracker.hpp"

namespace phasmid::solver {
using model::JetK;
using model::kJacobianChunk;

namespace {

constexpr int kMaxOrder = 12;  // Adams' maximum; BDF stops at 5

struct Run;

// One part's integrator and the polynomial through which the other parts read its angles.
struct PartSolver {
  const Run* run = nullptr;
  std::string name;
  std::vector<size_t> states;                         // global indices of its own states
  std::vector<size_t> inputs;                         // global indices of states it reads from others
  std::vector<std::pair<size_t, size_t>> input_from;  // per input: (part, index into that part's exports)
  std::vector<size_t> exports;                        // local indices of its states others read
  std::unique_ptr<model::OdeModelPart> eq;

  void* mem = nullptr;
  N_Vector y = nullptr, tmp = nullptr;
  SUNMatrix A = nullptr;
  SUNLinearSolver LS = nullptr;
  SUNNonlinearSolver NLS = nullptr;

  std::vector<double> yfull, ffull;  // full-size state and derivative for the part's equations
  std::vector<JetK> yK, fK;

  // Interpolating polynomial of the last step, as Taylor coefficients at t_poly:
  // coef[d * exports.size() + e] = (d^d y_e / dt^d)(t_poly) / d!.
  double t_poly = 0.0;
  int order = 0;
  std::vector<double> coef;

  double t = 0.0;        // time reached (CVODES' internal tn)
  size_t next_out = 0;   // first output time not yet written
  long steps_since_output = 0;  // against SolverOptions::max_steps (per output interval)
  std::vector<size_t> roots;          // global root indices watched by this part
  std::vector<size_t> root_state;     // their local state indices
  std::vector<size_t> pending_events; // events whose state this part has not yet passed
  SolverStats counters;               // over restarts (CVodeReInit resets CVODES' own)

  ~PartSolver() {
    if (NLS) SUNNonlinSolFree(NLS);
    if (mem) CVodeFree(&mem);
    if (LS) SUNLinSolFree(LS);
    if (A) SUNMatDestroy(A);
    if (tmp) N_VDestroy(tmp);
    if (y) N_VDestroy(y);
  }

  double export_value(size_t e, double at) const {
    const double dt = at - t_poly;
    const size_t ne = exports.size();
    double v = coef[static_cast<size_t>(order) * ne + e];
    for (int d = order - 1; d >= 0; --d) v = v * dt + coef[static_cast<size_t>(d) * ne + e];
    return v;
  }

  void update_polynomial() {
    if (exports.empty()) return;
    int q = 0;
    CVodeGetLastOrder(mem, &q);
    double tn = 0.0;
    CVodeGetCurrentTime(mem, &tn);
    const size_t ne = exports.size();
    double factorial = 1.0;
    for (int d = 0; d <= q; ++d) {
      if (d > 0) factorial *= d;
      check_cvodes(CVodeGetDky(mem, tn, d, tmp), "CVodeGetDky");
      for (size_t e = 0; e < ne; ++e) coef[static_cast<size_t>(d) * ne + e] = NV_Ith_S(tmp, exports[e]) / factorial;
    }
    order = q;
    t_poly = tn;
  }

  void add_counters() {
    long s = 0;
    CVodeGetNumSteps(mem, &s);
    counters.steps += s;
    add_cvodes_counters(mem, counters);
  }
  long total_steps() const {
    long v = 0;
    CVodeGetNumSteps(mem, &v);
    return counters.steps + v;
  }
};

struct Run {
  std::vector<std::unique_ptr<PartSolver>> parts;
  const std::vector<double>* p = nullptr;
  std::vector<JetK> pK;
  const std::vector<RootSpec>* roots = nullptr;
};

// Own states from CVODES, inputs from their owners' polynomials at time t.
template <class Scalar>
void fill_inputs(const PartSolver& ps, double t, std::vector<Scalar>& full) {
  for (size_t i = 0; i < ps.inputs.size(); ++i) {
    const auto& [owner, e] = ps.input_from[i];
    full[ps.inputs[i]] = Scalar(ps.run->parts[owner]->export_value(e, t));
  }
}

int part_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* ud) {
  auto* ps = static_cast<PartSolver*>(ud);
  fill_inputs(*ps, t, ps->yfull);
  const double* yv = N_VGetArrayPointer(y);
  for (size_t i = 0; i < ps->states.size(); ++i) ps->yfull[ps->states[i]] = yv[i];
  ps->eq->rhs(t, ps->yfull.data(), ps->run->p->data(), ps->ffull.data());
  double* out = N_VGetArrayPointer(ydot);
  for (size_t i = 0; i < ps->states.size(); ++i) {
    out[i] = ps->ffull[ps->states[i]];
    if (!std::isfinite(out[i])) return 1;  // recoverable: CVODES retries a smaller step
  }
  return 0;
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

struct ContextHandle {
  SUNContext ctx = nullptr;
  ~ContextHandle() {
    if (ctx) SUNContext_Free(&ctx);
  }
};

}  // namespace

SolveResult run_partitioned(const model::OdeModel& model, const model::ModelPartition& P, const SolverOptions& options,
                            const std::vector<double>& p_given, const std::vector<double>& output_times,
                            const std::vector<RootSpec>& caller_roots) {
  auto wall0 = std::chrono::steady_clock::now();
  const size_t n = model.num_states();
  // Triggered command times are "never" until their events (as in Simulator::run); each trigger
  // watches its threshold in both directions, after the caller's roots.
  const std::vector<model::CommandTrigger>& triggers = model.triggers();
  std::vector<double> p = p_given;
  for (const auto& tr : triggers)
    for (size_t k : tr.targets) p[k] = model::kUnresolvedMs;
  std::vector<RootSpec> roots = caller_roots;
  for (const auto& tr : triggers) roots.push_back({tr.state, tr.level_scale * p[tr.level_param], 0});
  const size_t n_out = output_times.size();
  const double t_end = output_times.back();
  const std::vector<double> y0 = model.initial_state(p);

  std::vector<size_t> part_of(n), local_of(n);
  for (size_t k = 0; k < P.size(); ++k)
    for (size_t i = 0; i < P.states[k].size(); ++i) {
      part_of[P.states[k][i]] = k;
      local_of[P.states[k][i]] = i;
    }

  ContextHandle ctx;  // declared before the parts: destroyed after them
  Run run;
  run.p = &p;
  run.roots = &roots;
  for (double v : p) run.pK.emplace_back(v);
  check_cvodes(SUNContext_Create(nullptr, &ctx.ctx), "SUNContext_Create");
  for (size_t k = 0; k < P.size(); ++k) {
    auto ps = std::make_unique<PartSolver>();
    ps->run = &run;
    ps->name = P.names[k];
    ps->states = P.states[k];
    ps->inputs = P.inputs[k];
    ps->eq = model.make_part(P, k);
    if (!ps->eq) throw Error("internal: model " + model.kind() + " has no equations for part " + ps->name);
    ps->yfull.assign(n, 0.0);
    ps->ffull.assign(n, 0.0);
    ps->yK.assign(n, JetK(0.0));
    ps->fK.assign(n, JetK(0.0));
    run.parts.push_back(std::move(ps));
  }
  // Who exports what to whom.
  for (auto& ps : run.parts)
    for (size_t g : ps->inputs) {
      PartSolver& owner = *run.parts[part_of[g]];
      const size_t local = local_of[g];
      auto at = std::find(owner.exports.begin(), owner.exports.end(), local);
      if (at == owner.exports.end()) at = owner.exports.insert(owner.exports.end(), local);
      ps->input_from.emplace_back(part_of[g], static_cast<size_t>(at - owner.exports.begin()));
    }
  for (size_t r = 0; r < roots.size(); ++r) {
    PartSolver& ps = *run.parts[part_of.at(roots[r].state)];
    ps.roots.push_back(r);
    ps.root_state.push_back(local_of[roots[r].state]);
  }

  std::vector<double> breaks = model.breakpoints(p, t_end);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::remove_if(breaks.begin(), breaks.end(), [&](double b) { return b <= 0.0 || b >= t_end; }),
               breaks.end());
  breaks.push_back(t_end);
  size_t next_break = 0;

  const bool adams = options.integrator == IntegratorKind::Adams;
  for (auto& psp : run.parts) {
    PartSolver& ps = *psp;
    const auto nk = static_cast<sunindextype>(ps.states.size());
    ps.y = N_VNew_Serial(nk, ctx.ctx);
    if (options.vector_kernels == VectorKernels::Phasmid) install_serial_kernels(ps.y);
    ps.tmp = N_VClone(ps.y);
    for (size_t i = 0; i < ps.states.size(); ++i) NV_Ith_S(ps.y, i) = y0[ps.states[i]];
    // Before its first step a part's polynomial is its initial value.
    ps.coef.assign(static_cast<size_t>(kMaxOrder + 1) * ps.exports.size(), 0.0);
    for (size_t e = 0; e < ps.exports.size(); ++e) ps.coef[e] = y0[ps.states[ps.exports[e]]];
    ps.mem = CVodeCreate(adams ? CV_ADAMS : CV_BDF, ctx.ctx);
    if (!ps.mem) throw SolverError("CVodeCreate failed");
    check_cvodes(CVodeInit(ps.mem, part_rhs, 0.0, ps.y), "CVodeInit");
    check_cvodes(CVodeSStolerances(ps.mem, options.rtol, options.atol), "CVodeSStolerances");
    check_cvodes(CVodeSetUserData(ps.mem, &ps), "CVodeSetUserData");
    apply_step_options(ps.mem, options);
    if (adams) {
      ps.NLS = SUNNonlinSol_FixedPoint(ps.y, 0, ctx.ctx);
      check_cvodes(CVodeSetNonlinearSolver(ps.mem, ps.NLS), "CVodeSetNonlinearSolver");
    } else {
      // Parts are small (a joint: 20-26 states): dense LU with the compiled kernels.
      ps.A = SUNDenseMatrix(nk, nk, ctx.ctx);
      ps.LS = SUNLinSol_Dense(ps.y, ps.A, ctx.ctx);
      if (options.vector_kernels == VectorKernels::Phasmid) install_dense_kernels(ps.A, ps.LS);
      check_cvodes(CVodeSetLinearSolver(ps.mem, ps.LS, ps.A), "CVodeSetLinearSolver");
      if (options.jacobian == JacobianKind::AutoDiff) check_cvodes(CVodeSetJacFn(ps.mem, part_jac), "CVodeSetJacFn");
    }
    if (!ps.roots.empty()) {
      std::vector<int> dirs;
      for (size_t r : ps.roots) dirs.push_back(roots[r].direction);
      check_cvodes(CVodeRootInit(ps.mem, static_cast<int>(ps.roots.size()), part_roots), "CVodeRootInit");
      check_cvodes(CVodeSetRootDirection(ps.mem, dirs.data()), "CVodeSetRootDirection");
      CVodeSetNoInactiveRootWarn(ps.mem);
    }
    check_cvodes(CVodeSetStopTime(ps.mem, breaks[0]), "CVodeSetStopTime");
  }

  SolveResult res;
  res.n_states = n;
  res.t = output_times;
  res.y.assign(n_out * n, NAN);
  res.steps_at_output.assign(n_out, 0);
  std::vector<size_t> parts_done(n_out, 0);  // parts that have written output k
  size_t first_out = 0;
  while (first_out < n_out && output_times[first_out] <= 0.0) {
    std::copy(y0.begin(), y0.end(), res.y.begin() + static_cast<long>(first_out * n));
    ++first_out;
  }
  for (auto& ps : run.parts) ps->next_out = first_out;
  auto total_steps = [&] {
    long s = 0;
    for (auto& ps : run.parts) s += ps->total_steps();
    return s;
  };
  // Writes part `ps`'s states at time t (within its last step) into the full-size state `row`.
  auto write_states = [&](PartSolver& ps, double t, double* row) {
    if (CVodeGetDky(ps.mem, t, 0, ps.tmp) < 0) {  // the scheduling guarantees t is in the last step
      double tn = 0.0, hu = 0.0;
      CVodeGetCurrentTime(ps.mem, &tn);
      CVodeGetLastStep(ps.mem, &hu);
      std::ostringstream os;
      os << "internal: part " << ps.name << " cannot interpolate at t = " << t << " ms (last step " << tn - hu
         << " .. " << tn << " ms); set [simulation] partitioned = false";
      throw SolverError(os.str());
    }
    for (size_t i = 0; i < ps.states.size(); ++i) row[ps.states[i]] = NV_Ith_S(ps.tmp, i);
  };

  // Trigger crossings wait until every part has passed them (an earlier crossing in a lagging
  // part may arm or fire a trigger first; in_stance reads other parts' states), then fire in
  // time order. A command at tau is a new synchronisation point: parts already beyond tau go
  // back to it (tau lies in their last step) and what they found after tau is discarded.
  std::vector<char> discarded;   // per entry of res.events
  std::vector<size_t> deferred;  // res.events entries that are trigger crossings not yet fed
  std::vector<TriggerTracker> trackers(triggers.size());
  auto roll_back = [&](PartSolver& x, double tau) {
    write_states(x, tau, x.yfull.data());
    for (size_t i = 0; i < x.states.size(); ++i) NV_Ith_S(x.y, i) = x.yfull[x.states[i]];
    x.add_counters();
    check_cvodes(CVodeReInit(x.mem, tau, x.y), "CVodeReInit");
    x.t = tau;
    while (x.next_out > first_out && output_times[x.next_out - 1] > tau) --parts_done[--x.next_out];
  };
  auto add_command_time = [&](double tau) {
    const auto at = std::lower_bound(breaks.begin() + static_cast<long>(next_break), breaks.end(), tau);
    if (std::abs(*at - tau) <= 1e-9 * std::max(1.0, tau)) return;  // already a synchronisation point
    const bool next = at == breaks.begin() + static_cast<long>(next_break);
    breaks.insert(at, tau);
    if (!next) return;  // later than the next one: every part is before it
    for (auto& x : run.parts) {
      if (x->t > tau) roll_back(*x, tau);
      else if (x->t < tau) check_cvodes(CVodeSetStopTime(x->mem, tau), "CVodeSetStopTime");
    }
    for (size_t id = 0; id < res.events.size(); ++id)
      if (res.events[id].t > tau) discarded[id] = 1;
    deferred.erase(std::remove_if(deferred.begin(), deferred.end(), [&](size_t id) { return discarded[id] != 0; }),
                   deferred.end());
    for (auto& x : run.parts)
      x->pending_events.erase(std::remove_if(x->pending_events.begin(), x->pending_events.end(),
                                             [&](size_t id) { return discarded[id] != 0; }),
                              x->pending_events.end());
  };
  auto feed_triggers = [&] {
    double t_min = INFINITY;
    for (auto& x : run.parts) t_min = std::min(t_min, x->t);
    for (;;) {
      auto next = std::min_element(deferred.begin(), deferred.end(),
                                   [&](size_t a, size_t b) { return res.events[a].t < res.events[b].t; });
      if (next == deferred.end() || res.events[*next].t > t_min) return;
      const size_t id = *next;
      deferred.erase(next);
      const Event& e = res.events[id];
      const size_t k = e.root - caller_roots.size();
      if (!trackers[k].fires(triggers[k], e.t, e.direction, p, e.y.data())) continue;
      const double tau = e.t + triggers[k].delay_ms;
      for (size_t q : triggers[k].targets) {
        p[q] = tau;
        run.pK[q] = JetK(tau);
        res.commands.push_back({q, tau, k});
      }
      if (tau < t_end) add_command_time(tau);
    }
  };

  const bool show_progress = options.progress && isatty(STDERR_FILENO);
  auto last_print = std::chrono::steady_clock::now();
  std::vector<int> found;
  for (;;) {
    // The part furthest behind steps next (see the header); parts at the breakpoint wait.
    PartSolver* lag = nullptr;
    for (auto& ps : run.parts)
      if (ps->t < breaks[next_break] && (!lag || ps->t < lag->t)) lag = ps.get();
    if (!lag) {
      if (next_break + 1 == breaks.size()) break;
      // All parts are at a central command: restart each from its state there.
      const double tb = breaks[next_break++];
      for (auto& ps : run.parts) {
        ps->add_counters();
        check_cvodes(CVodeReInit(ps->mem, tb, ps->y), "CVodeReInit");
        check_cvodes(CVodeSetStopTime(ps->mem, breaks[next_break]), "CVodeSetStopTime");
      }
      ++res.stats.restarts;
      continue;
    }
    PartSolver& ps = *lag;
    double tret = ps.t;
    const int flag = CVode(ps.mem, breaks[next_break], ps.y, &tret, CV_ONE_STEP);
    // CV_ONE_STEP never reports CV_TOO_MUCH_WORK: the same limit per output interval here.
    const bool too_much_work = ++ps.steps_since_output > options.max_steps;
    if (flag < 0 || too_much_work) {
      std::ostringstream os;
      os << "CVODES failed at t = " << tret << " ms in part " << ps.name << ": "
         << (too_much_work ? "CV_TOO_MUCH_WORK" : CVodeGetReturnFlagName(flag))
         << " (try --set on the offending parameter, tighter tolerances, or partitioned = false)";
      throw SolverError(os.str());
    }
    if (flag == CV_TSTOP_RETURN) {
      ps.t = breaks[next_break];
    } else {
      CVodeGetCurrentTime(ps.mem, &ps.t);
    }
    ps.update_polynomial();
    // Every root of this step is taken now, before another part steps on: a second call in
    // CV_NORMAL mode to the time reached returns the step's remaining roots one by one and
    // then y(t) without stepping. (Another part's next step could otherwise leave the time
    // of a later root of this step, where its state is interpolated.)
    for (int f = flag; f == CV_ROOT_RETURN;) {
      found.assign(ps.roots.size(), 0);
      check_cvodes(CVodeGetRootInfo(ps.mem, found.data()), "CVodeGetRootInfo");
      for (size_t r = 0; r < ps.roots.size(); ++r) {
        if (!found[r]) continue;
        Event e;
        e.t = tret;
        e.root = ps.roots[r];
        e.direction = found[r];
        e.y.assign(n, NAN);
        for (size_t i = 0; i < ps.states.size(); ++i) e.y[ps.states[i]] = NV_Ith_S(ps.y, i);  // y(tret)
        res.events.push_back(std::move(e));
        discarded.push_back(0);
        const size_t id = res.events.size() - 1;
        if (ps.roots[r] >= caller_roots.size()) deferred.push_back(id);
        // Parts past the event interpolate now (its time lies in their last step: each part's
        // last step began at or before the lagging part's time); the others when they get there.
        for (auto& other : run.parts) {
          if (other.get() == &ps) continue;
          if (other->t >= tret) write_states(*other, tret, res.events[id].y.data());
          else other->pending_events.push_back(id);
        }
      }
      f = CVode(ps.mem, ps.t, ps.y, &tret, CV_NORMAL);
      if (f < 0) check_cvodes(f, "CVode (roots of the last step)");
    }
    // Outputs and pending event states up to the time reached.
    while (ps.next_out < n_out && output_times[ps.next_out] <= ps.t) {
      const size_t k = ps.next_out++;
      ps.steps_since_output = 0;
      write_states(ps, output_times[k], &res.y[k * n]);
      if (++parts_done[k] == run.parts.size()) res.steps_at_output[k] = total_steps();
    }
    for (size_t i = 0; i < ps.pending_events.size();) {
      const size_t id = ps.pending_events[i];
      if (res.events[id].t <= ps.t) {
        write_states(ps, res.events[id].t, res.events[id].y.data());
        ps.pending_events.erase(ps.pending_events.begin() + static_cast<long>(i));
      } else {
        ++i;
      }
    }
    if (!deferred.empty()) feed_triggers();
    if (show_progress) {
      auto now = std::chrono::steady_clock::now();
      if (now - last_print > std::chrono::milliseconds(200)) {
        std::fprintf(stderr, "\r%s: t = %.0f / %.0f ms (%3.0f%%, %zu parts)", options.progress_label.c_str(), ps.t,
                     t_end, 100.0 * ps.t / t_end, run.parts.size());
        last_print = now;
      }
    }
  }
  if (show_progress)
    std::fprintf(stderr, "\r%s: t = %.0f / %.0f ms (100%%, %zu parts)\n", options.progress_label.c_str(), t_end, t_end,
                 run.parts.size());

  // The caller's events in time order, each with the full right-hand side at its state.
  std::vector<Event> kept;
  for (size_t id = 0; id < res.events.size(); ++id)
    if (!discarded[id] && res.events[id].root < caller_roots.size()) kept.push_back(std::move(res.events[id]));
  res.events = std::move(kept);
  std::stable_sort(res.events.begin(), res.events.end(), [](const Event& a, const Event& b) { return a.t < b.t; });
  for (Event& e : res.events) {
    e.ydot.assign(n, 0.0);
    model.rhs(e.t, e.y.data(), p.data(), e.ydot.data());
  }
  for (auto& ps : run.parts) {
    ps->add_counters();
    const SolverStats& c = ps->counters;
    res.stats.steps += c.steps;
    res.stats.rhs_evals += c.rhs_evals;
    res.stats.jac_evals += c.jac_evals;
    res.stats.error_test_failures += c.error_test_failures;
    res.stats.newton_iterations += c.newton_iterations;
    res.stats.newton_failures += c.newton_failures;
    res.stats.linear_setups += c.linear_setups;
  }
  res.stats.integrators = static_cast<long>(run.parts.size());
  res.stats.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return res;
}

}  // namespace phasmid::solver
