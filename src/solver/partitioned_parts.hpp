#pragma once
// The partitioned driver's shared plumbing (solver/partitioned_simulator.hpp): one part's
// integrator and the polynomial through which the others read it (PartSolver), the run's parts
// (Run), their assembly and their sessions. The schedulers that step them are the member
// functions of Partitioned (solver/partitioned_driver.hpp), one file each:
// partitioned_sequential.cpp (threads = 1), partitioned_windowed.cpp (threads >= 2 with
// triggers) and partitioned_grid.cpp (threads >= 2 without triggers).
#include <cvodes/cvodes.h>
#include <nvector/nvector_serial.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "model/ode_model.hpp"
#include "solver/cvodes_session.hpp"
#include "solver/integrator_session.hpp"
#include "solver/run_parameters.hpp"
#include "solver/solver_options.hpp"
#include "solver/solver_result.hpp"
#include "solver/step_history.hpp"

namespace phasmid::solver::partitioned {

using model::JetK;

constexpr int kMaxOrder = 5;    // the highest degree of a part's polynomial: CVODES BDF's order
constexpr long kGridBatch = 8;  // windows per call of Partitioned::advance_on_grid
// Windowed runs: a snapshot is extrapolated beyond its part's last step with at most this many
// derivatives (the result depends on it; 3 is the cubic Hermite of a Dormand-Prince step).
constexpr int kWindowOrder = 3;
// Windowed runs without triggers: a part may complete up to this many windows ahead of the
// slowest, while a thread would otherwise wait. Changes no number.
constexpr long kWindowLookAhead = 16;

struct Run;

// Taylor coefficients c[d * stride + e] of entry e at a point, evaluated dt after it.
inline double horner(const std::vector<double>& c, size_t stride, size_t e, int order, double dt) {
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
  const std::vector<double>* p = nullptr;  // the run's parameters (RunParameters::values)
  std::vector<JetK> pK;                    // as Jets, a mirror kept in step by RunParameters
  const std::vector<RootSpec>* roots = nullptr;
  bool windowed = false;  // parts read each other's snapshots (SolverOptions::threads >= 2)
};

// The parts of P with their equations (bound to `params`), who reads whose exports, and which
// roots each watches.
void build_parts(Run& run, RunParameters& params, const model::OdeModel& model, const model::ModelPartition& P,
                 const std::vector<RootSpec>& roots, const SolverOptions& options);
// Each part's integrator from y0, integrating towards the first stop; contexts: one for all
// parts, or one per part (windowed runs: no two threads share one).
void start_sessions(Run& run, const model::OdeModel& model, const std::vector<std::unique_ptr<SundialsContext>>& contexts,
                    const SolverOptions& options, const std::vector<double>& y0, double first_stop);

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

}  // namespace phasmid::solver::partitioned
