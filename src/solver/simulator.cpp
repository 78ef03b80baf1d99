#include "solver/simulator.hpp"

#include <cvodes/cvodes.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_band.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "common/error.hpp"
#include "solver/command_schedule.hpp"
#include "solver/cvodes_session.hpp"
#include "solver/erk_session.hpp"
#include "solver/output_sink.hpp"
#include "solver/partitioned_simulator.hpp"
#include "solver/run_loop.hpp"

namespace phasmid::solver {

void compile_if_asked(model::OdeModelPart* part, const SolverOptions& options) {
  if (!options.compiled_rhs) return;
  std::string why = "this model kind has no compiled right-hand side";
  if (part && part->compile(&why)) return;
  static std::atomic<bool> warned{false};
  if (!warned.exchange(true))
    std::fprintf(stderr, "phasmid: warning: compiled_rhs: %s; the generic right-hand side runs instead\n", why.c_str());
}
using model::Jet1;
using model::Jet4;
using model::JetK;
using model::kJacobianChunk;
using model::OdeModel;

namespace {

// Scratch vectors of one scalar type for model evaluations: states, parameters (their values;
// derivative lanes are seeded and cleared around each evaluation) and right-hand side.
template <class J>
struct JetScratch {
  std::vector<J> y, p, f;
  void init(size_t n, const std::vector<double>& values) {
    y.assign(n, J(0.0));
    f.assign(n, J(0.0));
    p.clear();
    for (double v : values) p.emplace_back(v);
  }
};

// Everything the C callbacks need; lives for one run().
struct CallbackData {
  const OdeModel* model;
  const std::vector<double>* p;
  std::unique_ptr<model::OdeModelPart> eq;  // the model bound to *p (make_whole), or none
  const std::vector<RootSpec>* roots;
  std::vector<size_t> sens_params;
  size_t n;
  JetScratch<JetK> jK;  // Jacobian columns, sensitivity chunks of five to eight
  JetScratch<Jet4> j4;  // sensitivity chunks of two to four
  JetScratch<Jet1> j1;  // one sensitivity
  void init_scratch(const std::vector<double>& values) {
    jK.init(n, values);
    j4.init(n, values);
    j1.init(n, values);
  }
  // A parameter set during the run (a triggered command time).
  void set_parameter(size_t q, double value) {
    jK.p[q] = JetK(value);
    j4.p[q] = Jet4(value);
    j1.p[q] = Jet1(value);
  }
  long sens_evals = 0;
  // Sparse (KLU) Jacobians: column-compressed pattern and a column colouring (columns of one
  // colour share no row, so one AD direction per colour gives all of them: Curtis-Powell-Reid).
  std::vector<sunindextype> col_ptr, row_idx;
  std::vector<size_t> color;
  size_t n_colors = 0;
};

int rhs_cb(sunrealtype t, N_Vector y, N_Vector ydot, void* ud) {
  auto* d = static_cast<CallbackData*>(ud);
  if (d->eq) d->eq->rhs(t, N_VGetArrayPointer(y), d->p->data(), N_VGetArrayPointer(ydot));
  else d->model->rhs(t, N_VGetArrayPointer(y), d->p->data(), N_VGetArrayPointer(ydot));
  for (size_t i = 0; i < d->n; ++i)
    if (!std::isfinite(NV_Ith_S(ydot, i))) return 1;  // recoverable: CVODES retries a smaller step
  return 0;
}

// Fills the dense column-major Jacobian `J` (n x n) by forward-mode AD in chunks of columns.
void fill_jacobian(CallbackData* d, double t, const double* y, double* J) {
  const size_t n = d->n;
  for (size_t c0 = 0; c0 < n; c0 += kJacobianChunk) {
    for (size_t i = 0; i < n; ++i) {
      d->jK.y[i] = JetK(y[i]);
      if (i >= c0 && i < c0 + kJacobianChunk) d->jK.y[i].v[i - c0] = 1.0;
    }
    d->model->rhs(t, d->jK.y.data(), d->jK.p.data(), d->jK.f.data());
    for (size_t k = 0; k < kJacobianChunk && c0 + k < n; ++k)
      for (size_t i = 0; i < n; ++i) J[(c0 + k) * n + i] = d->jK.f[i].v[k];
  }
}

int jac_dense_cb(sunrealtype t, N_Vector y, N_Vector, SUNMatrix Jm, void* ud, N_Vector, N_Vector, N_Vector) {
  auto* d = static_cast<CallbackData*>(ud);
  fill_jacobian(d, t, N_VGetArrayPointer(y), SUNDenseMatrix_Data(Jm));
  return 0;
}

int jac_band_cb(sunrealtype t, N_Vector y, N_Vector, SUNMatrix Jm, void* ud, N_Vector, N_Vector, N_Vector) {
  auto* d = static_cast<CallbackData*>(ud);
  std::vector<double> J(d->n * d->n);
  fill_jacobian(d, t, N_VGetArrayPointer(y), J.data());
  const long mu = SUNBandMatrix_UpperBandwidth(Jm), ml = SUNBandMatrix_LowerBandwidth(Jm);
  for (long j = 0; j < static_cast<long>(d->n); ++j) {
    sunrealtype* col = SUNBandMatrix_Column(Jm, j);
    for (long i = std::max(0L, j - mu); i <= std::min<long>(d->n - 1, j + ml); ++i)
      SM_COLUMN_ELEMENT_B(col, i, j) = J[j * d->n + i];
  }
  return 0;
}

// Values `v` (in the order of d->row_idx) of the sparse Jacobian by coloured forward-mode AD:
// ceil(n_colors / chunk) evaluations instead of ceil(n / chunk).
void fill_sparse_jacobian(CallbackData* d, double t, const double* yv, double* v) {
  for (size_t c0 = 0; c0 < d->n_colors; c0 += kJacobianChunk) {
    for (size_t i = 0; i < d->n; ++i) {
      d->jK.y[i] = JetK(yv[i]);
      if (d->color[i] >= c0 && d->color[i] < c0 + kJacobianChunk) d->jK.y[i].v[d->color[i] - c0] = 1.0;
    }
    d->model->rhs(t, d->jK.y.data(), d->jK.p.data(), d->jK.f.data());
    for (size_t j = 0; j < d->n; ++j) {
      if (d->color[j] < c0 || d->color[j] >= c0 + kJacobianChunk) continue;
      for (sunindextype k = d->col_ptr[j]; k < d->col_ptr[j + 1]; ++k) v[k] = d->jK.f[d->row_idx[k]].v[d->color[j] - c0];
    }
  }
}

int jac_sparse_cb(sunrealtype t, N_Vector y, N_Vector, SUNMatrix Jm, void* ud, N_Vector, N_Vector, N_Vector) {
  auto* d = static_cast<CallbackData*>(ud);
  std::copy(d->col_ptr.begin(), d->col_ptr.end(), SUNSparseMatrix_IndexPointers(Jm));
  std::copy(d->row_idx.begin(), d->row_idx.end(), SUNSparseMatrix_IndexValues(Jm));
  fill_sparse_jacobian(d, t, N_VGetArrayPointer(y), SUNSparseMatrix_Data(Jm));
  return 0;
}

// Structural sparsity of df/dy: union of the nonzeros of AD Jacobians at the initial state and
// at randomly perturbed states (deterministic seed), plus the diagonal (needed by I - gamma J).
void sparsity_pattern(CallbackData* d, const std::vector<double>& y0) {
  const size_t n = d->n;
  std::vector<char> nz(n * n, 0);
  std::vector<double> J(n * n), y(n);
  unsigned long long state = 0x9E3779B97F4A7C15ULL;
  auto uniform = [&] {
    state ^= state << 13; state ^= state >> 7; state ^= state << 17;
    return (state >> 11) * (1.0 / 9007199254740992.0);
  };
  // Samples at t = 0 and at a late time, so that entries gated by central commands (steps at
  // given times, zero before them) are in the pattern too: with coloured Jacobians an entry
  // missing from the pattern would be added to another column of its colour.
  for (int sample = 0; sample < 8; ++sample) {
    for (size_t i = 0; i < n; ++i) y[i] = sample % 4 == 0 ? y0[i] : y0[i] + (uniform() - 0.5) * (0.2 + 0.2 * std::abs(y0[i]));
    fill_jacobian(d, sample < 4 ? 0.0 : 1e10, y.data(), J.data());
    for (size_t k = 0; k < n * n; ++k)
      if (J[k] != 0.0) nz[k] = 1;
  }
  d->col_ptr.assign(1, 0);
  d->row_idx.clear();
  for (size_t j = 0; j < n; ++j) {
    for (size_t i = 0; i < n; ++i)
      if (nz[j * n + i] || i == j) d->row_idx.push_back(static_cast<sunindextype>(i));
    d->col_ptr.push_back(static_cast<sunindextype>(d->row_idx.size()));
  }
  // Greedy colouring: a column takes the smallest colour not used by a column sharing a row.
  std::vector<std::vector<size_t>> cols_of_row(n);
  for (size_t j = 0; j < n; ++j)
    for (sunindextype k = d->col_ptr[j]; k < d->col_ptr[j + 1]; ++k) cols_of_row[d->row_idx[k]].push_back(j);
  d->color.assign(n, SIZE_MAX);
  d->n_colors = 0;
  std::vector<size_t> used_by(n + 1, SIZE_MAX);  // used_by[c] == j: colour c is taken for column j
  for (size_t j = 0; j < n; ++j) {
    for (sunindextype k = d->col_ptr[j]; k < d->col_ptr[j + 1]; ++k)
      for (size_t other : cols_of_row[d->row_idx[k]])
        if (d->color[other] != SIZE_MAX) used_by[d->color[other]] = j;
    size_t c = 0;
    while (used_by[c] == j) ++c;
    d->color[j] = c;
    d->n_colors = std::max(d->n_colors, c + 1);
  }
}

// Sensitivity right-hand sides J s + df/dp of the m parameters first .. first+m-1 (yS[k],
// ySdot[k] belong to parameter first+k) in one Jet<N> evaluation, m <= N: lane k carries
// yS[k] and the unit seed of that parameter.
template <class J>
void sens_rhs_chunk(CallbackData* d, JetScratch<J>& w, sunrealtype t, const double* yv, int first, int m,
                    const N_Vector* yS, N_Vector* ySdot) {
  for (size_t i = 0; i < d->n; ++i) w.y[i] = J(yv[i]);
  for (int k = 0; k < m; ++k) {
    const double* sv = N_VGetArrayPointer(yS[k]);
    for (size_t i = 0; i < d->n; ++i) w.y[i].v[k] = sv[i];
    w.p[d->sens_params[first + k]].v[k] = 1.0;
  }
  d->model->rhs(t, w.y.data(), w.p.data(), w.f.data());
  for (int k = 0; k < m; ++k) {
    w.p[d->sens_params[first + k]].v[k] = 0.0;
    double* out = N_VGetArrayPointer(ySdot[k]);
    for (size_t i = 0; i < d->n; ++i) out[i] = w.f[i].v[k];
  }
  d->sens_evals += m;
}

// One sensitivity right-hand side (CVodeSensInit1): a Jet<1> evaluation.
int sens_rhs_cb(int, sunrealtype t, N_Vector y, N_Vector, int is, N_Vector yS, N_Vector ySdot, void* ud, N_Vector,
                N_Vector) {
  auto* d = static_cast<CallbackData*>(ud);
  sens_rhs_chunk(d, d->j1, t, N_VGetArrayPointer(y), is, 1, &yS, &ySdot);
  return 0;
}

// All sensitivity right-hand sides at once: chunks of kJacobianChunk parameters share one
// Jet<kJacobianChunk> evaluation, a last chunk of at most four a Jet<4> one.
int sens_rhs_batched_cb(int ns, sunrealtype t, N_Vector y, N_Vector, N_Vector* yS, N_Vector* ySdot, void* ud,
                        N_Vector, N_Vector) {
  auto* d = static_cast<CallbackData*>(ud);
  const double* yv = N_VGetArrayPointer(y);
  for (int c0 = 0; c0 < ns; c0 += kJacobianChunk) {
    const int m = std::min(kJacobianChunk, ns - c0);
    if (m <= 4) sens_rhs_chunk(d, d->j4, t, yv, c0, m, yS + c0, ySdot + c0);
    else sens_rhs_chunk(d, d->jK, t, yv, c0, m, yS + c0, ySdot + c0);
  }
  return 0;
}

int root_cb(sunrealtype, N_Vector y, sunrealtype* g, void* ud) {
  auto* d = static_cast<CallbackData*>(ud);
  const auto& roots = *d->roots;
  for (size_t r = 0; r < roots.size(); ++r) g[r] = NV_Ith_S(y, roots[r].state) - roots[r].level;
  return 0;
}

}  // namespace

Simulator::Simulator(const OdeModel& model, SolverOptions options) : model_(model), options_(options) {}

OutputTimes OutputTimes::grid(double t_end, double dt) {
  if (!(dt > 0) || !(t_end > 0)) throw Error("output grid needs t_end > 0 and dt > 0");
  OutputTimes g;
  g.n_grid_ = static_cast<size_t>(std::floor(t_end / dt + 1e-9)) + 1;
  g.dt_ = dt;
  g.t_end_ = t_end;
  g.n_ = g.n_grid_ + (t_end - static_cast<double>(g.n_grid_ - 1) * dt > 1e-9 ? 1 : 0);
  return g;
}

std::vector<double> OutputTimes::to_vector() const {
  if (list_) return *list_;
  std::vector<double> t(n_);
  for (size_t k = 0; k < n_; ++k) t[k] = (*this)[k];
  return t;
}

std::vector<double> output_grid(double t_end, double dt) { return OutputTimes::grid(t_end, dt).to_vector(); }

namespace {
CallbackData jacobian_data(const OdeModel& model, const std::vector<double>& p) {
  CallbackData d;
  d.model = &model;
  d.p = &p;
  d.n = model.num_states();
  d.jK.init(d.n, p);
  return d;
}
}  // namespace

std::vector<double> jacobian_autodiff(const OdeModel& model, double t, const std::vector<double>& y,
                                      const std::vector<double>& p) {
  CallbackData d = jacobian_data(model, p);
  std::vector<double> J(d.n * d.n);
  fill_jacobian(&d, t, y.data(), J.data());
  return J;
}

std::vector<double> jacobian_sparse_autodiff(const OdeModel& model, double t, const std::vector<double>& y,
                                             const std::vector<double>& p, size_t* n_colors) {
  CallbackData d = jacobian_data(model, p);
  sparsity_pattern(&d, model.initial_state(p));
  if (n_colors) *n_colors = d.n_colors;
  std::vector<double> v(d.row_idx.size()), J(d.n * d.n, 0.0);
  fill_sparse_jacobian(&d, t, y.data(), v.data());
  for (size_t j = 0; j < d.n; ++j)
    for (sunindextype k = d.col_ptr[j]; k < d.col_ptr[j + 1]; ++k) J[j * d.n + d.row_idx[k]] = v[k];
  return J;
}

namespace {

// The newton linear system of the whole model (SolverOptions::linear_solver, Auto by size);
// the KLU path needs the Jacobian's sparsity pattern, computed here into d.
void attach_linear_solver(CvodesSession& session, CallbackData& d, const OdeModel& model,
                          const SolverOptions& options, const std::vector<double>& y0, size_t ns) {
  const int bw = model.jacobian_half_bandwidth();
  const bool band = options.linear_solver == LinearSolverKind::Band && bw >= 0;
  // KLU needs an exact Jacobian function (a difference quotient is only available for dense/band).
  const bool want_klu = options.linear_solver == LinearSolverKind::Klu ||
                        (options.linear_solver == LinearSolverKind::Auto &&
                         d.n > (ns > 0 ? kDenseMaxStatesWithSensitivities : kDenseMaxStates));
  const bool klu = want_klu && options.jacobian == JacobianKind::AutoDiff;
  const bool adams = options.integrator == IntegratorKind::Adams;
  if (klu && !adams) sparsity_pattern(&d, y0);
  const LinearSystem kind = band ? LinearSystem::Band : klu ? LinearSystem::Sparse : LinearSystem::Dense;
  CVLsJacFn jac = band ? jac_band_cb : klu ? jac_sparse_cb : jac_dense_cb;
  if (options.jacobian != JacobianKind::AutoDiff) jac = nullptr;
  session.set_linear_solver(kind, bw, static_cast<long>(d.row_idx.size()), jac);
}

// Forward sensitivities from s(0) = dy0/dp: initial states are algebraic (at most linear)
// functions of the parameters (e.g. initial joint angles), so a central difference is exact.
void init_sensitivities(CvodesSession& session, const OdeModel& model, const std::vector<double>& p,
                        const std::vector<size_t>& sens_params) {
  const size_t n = model.num_states();
  std::vector<std::vector<double>> s0(sens_params.size(), std::vector<double>(n));
  std::vector<double> pbar(sens_params.size());
  for (size_t j = 0; j < sens_params.size(); ++j) {
    const size_t k = sens_params[j];
    const auto [yp, ym, hstep] =
        central_pair(p, k, [&](const std::vector<double>& q) { return model.initial_state(q); });
    for (size_t i = 0; i < n; ++i) s0[j][i] = (yp[i] - ym[i]) / (2 * hstep);
    pbar[j] = std::abs(p[k]) > 0 ? std::abs(p[k]) : 1.0;
  }
  session.init_sensitivities(s0, sens_rhs_batched_cb, sens_rhs_cb, pbar);
}

// The whole model as one CVODES system (the Driver of run_loop): each advance integrates to
// the next output time; triggers fire at once at their crossings.
class WholeSystem {
 public:
  WholeSystem(const OdeModel& model, const SolverOptions& options, const CommandSchedule& schedule,
              IntegratorSession& session, CallbackData& d, const OutputTimes& output_times,
              size_t n_caller_roots, SolveResult& res)
      : model_(model), options_(options), schedule_(schedule), session_(session), d_(d),
        output_times_(output_times), n_caller_roots_(n_caller_roots), res_(res), ns_(d.sens_params.size()),
        ydot_(d.n), rootsfound_(d.roots->size()) {
    if (output_times[0] <= 0.0) {
      record(0.0, false);
      k_out_ = 1;
    }
  }
  bool finished(const CommandSchedule&) const { return k_out_ == output_times_.size(); }
  double advance(CommandSchedule&);
  void handle_events(CommandSchedule& schedule);
  bool at_stop(const CommandSchedule& schedule) const {
    return flag_ == CV_TSTOP_RETURN && std::abs(t_ - schedule.next_stop()) < 1e-9;
  }
  void restart(double, const std::vector<double>& dtau_dp, double next_stop) {
    // The right-hand side changes here: restart from the current state. Sensitivities carry
    // over, plus a jump if the switch time moves with p.
    restart_here(dtau_dp);
    session_.set_stop_time(next_stop);
  }
  void record_outputs() {
    const double tout = output_times_[k_out_ < output_times_.size() ? k_out_ : 0];
    if (k_out_ < output_times_.size() && flag_ != kNone && std::abs(t_ - tout) < 1e-9 * std::max(1.0, std::abs(tout))) {
      record(tout, flag_ == CV_SUCCESS);  // events and restarts fetched them already
      ++k_out_;
    }
  }

 private:
  static constexpr int kNone = -1000;  // no advance yet
  void fire_triggers(CommandSchedule& schedule, std::vector<double>& dtau_now, bool& restart_now);
  void record_events();
  void record(double t, bool fetch_sens);
  void restart_here(const std::vector<double>& dtau_dp);
  std::vector<double*> sens_columns() const;

  const OdeModel& model_;
  const SolverOptions& options_;
  const CommandSchedule& schedule_;
  IntegratorSession& session_;
  CallbackData& d_;
  const OutputTimes& output_times_;
  const size_t n_caller_roots_;
  SolveResult& res_;
  const size_t ns_;
  std::vector<double> ydot_;
  std::vector<int> rootsfound_;
  size_t k_out_ = 0;
  double t_ = 0.0;
  int flag_ = kNone;
};

double WholeSystem::advance(CommandSchedule&) {
  flag_ = session_.advance(output_times_[k_out_], &t_, CV_NORMAL);
  if (flag_ < 0) {
    std::ostringstream os;
    os << session_.package() << " failed at t = " << t_ << " ms: " << session_.flag_name(flag_)
       << " " << failure_advice(options_, false);
    throw SolverError(os.str());
  }
  // Sensitivities are needed at events, at restarts and (if kept) at output times (record
  // fetches those).
  if (ns_ && (flag_ == CV_ROOT_RETURN || flag_ == CV_TSTOP_RETURN)) session_.fetch_sensitivities();
  return t_;
}

void WholeSystem::handle_events(CommandSchedule& schedule) {
  if (flag_ != CV_ROOT_RETURN) return;
  session_.root_info(rootsfound_.data());
  model_.rhs(t_, N_VGetArrayPointer(session_.y()), schedule.p().data(), ydot_.data());
  std::vector<double> dtau_now(ns_, 0.0);  // d tau / dp of commands triggered at this event
  bool restart_now = false;
  fire_triggers(schedule, dtau_now, restart_now);
  record_events();
  if (restart_now) {
    // A trigger set a command time to this very event: the right-hand side changes here;
    // s(t+) = s(t-) + (f(t-) - f(t+)) d t_event / dp. The restart is also needed without a
    // jump: at a root return CVODES' own sensitivities are at its internal time beyond the
    // root, the ones fetched at the root.
    restart_here(dtau_now);
  }
}

void WholeSystem::fire_triggers(CommandSchedule& schedule, std::vector<double>& dtau_now, bool& restart_now) {
  const double* y = N_VGetArrayPointer(session_.y());
  for (size_t k = 0; k < schedule.triggers().size(); ++k) {
    const int dir = rootsfound_[n_caller_roots_ + k];
    if (!dir || !schedule.fire(k, t_, dir, y, res_.commands)) continue;
    const model::CommandTrigger& tr = schedule.triggers()[k];
    const double when = t_ + tr.delay_ms;
    for (size_t q : tr.targets) d_.set_parameter(q, when);
    if (d_.eq) d_.eq->bind(schedule.p().data());
    std::vector<double> dte;
    if (ns_) {
      std::vector<double> s_state(ns_);
      for (size_t j = 0; j < ns_; ++j) s_state[j] = NV_Ith_S(session_.s()[j], tr.state);
      dte = schedule.crossing_time_sensitivity(k, t_, ydot_[tr.state], s_state);
    }
    if (when <= t_ + 1e-9 * std::max(1.0, std::abs(t_))) {
      // The jump is applied after this event's sensitivities are recorded (they are s(t-)).
      restart_now = true;
      schedule.merge_jump(dtau_now, dte, k);
    } else if (when < schedule.t_end()) {
      // A later command: one more stop. The sensitivity is continuous at the event; it jumps
      // at tau with d tau / dp = d t_event / dp found here.
      if (schedule.add_command_time(when, dte, k) != CommandSchedule::Added::Existing)
        session_.set_stop_time(schedule.next_stop());
    }
  }
}

void WholeSystem::record_events() {
  const double* y = N_VGetArrayPointer(session_.y());
  const size_t n = d_.n;
  for (size_t r = 0; r < n_caller_roots_; ++r) {
    if (!rootsfound_[r]) continue;
    Event e;
    e.t = t_;
    e.root = r;
    e.direction = rootsfound_[r];
    e.y.assign(y, y + n);
    e.ydot = ydot_;
    if (ns_) {
      e.s.resize(n * ns_);
      for (size_t i = 0; i < n; ++i)
        for (size_t j = 0; j < ns_; ++j) e.s[i * ns_ + j] = NV_Ith_S(session_.s()[j], i);
    }
    res_.events.push_back(std::move(e));
  }
}

void WholeSystem::record(double t, bool fetch_sens) {
  if (options_.output_sink) {
    options_.output_sink->record(t, N_VGetArrayPointer(session_.y()), d_.n);
    res_.t.assign(1, t);
    return;
  }
  res_.t.push_back(t);
  res_.steps_at_output.push_back(session_.total_steps());
  const size_t n = d_.n;
  for (size_t i = 0; i < n; ++i) res_.y.push_back(NV_Ith_S(session_.y(), i));
  if (ns_ && options_.sensitivities_at_outputs) {
    if (fetch_sens) session_.fetch_sensitivities();
    for (size_t i = 0; i < n; ++i)
      for (size_t j = 0; j < ns_; ++j) res_.s.push_back(NV_Ith_S(session_.s()[j], i));
  }
}

void WholeSystem::restart_here(const std::vector<double>& dtau_dp) {
  if (ns_) schedule_.apply_jump(t_, dtau_dp, N_VGetArrayPointer(session_.y()), sens_columns());
  session_.restart(t_);
  ++res_.stats.restarts;
}

std::vector<double*> WholeSystem::sens_columns() const {
  std::vector<double*> s(ns_);
  for (size_t j = 0; j < ns_; ++j) s[j] = N_VGetArrayPointer(session_.s()[j]);
  return s;
}

}  // namespace

SolveResult Simulator::run(const std::vector<double>& p_given, const OutputTimes& output_times,
                           const std::vector<RootSpec>& roots, const std::vector<size_t>& sens_params) const {
  const SolveTimer timer;
  if (p_given.size() != model_.parameters().size()) throw Error("internal: parameter vector size mismatch");
  if (output_times.empty() || output_times.front() < 0) throw Error("output times must start at t >= 0");
  const size_t ns = sens_params.size();
  if (ns && options_.output_sink) throw Error("internal: an output sink takes no sensitivities");
  check_atol_units(model_, options_);
  const bool partition = options_.partitioning == Partitioning::On || options_.partitioning == Partitioning::Neurons;
  if (partition && ns == 0) {
    if (options_.partitioning == Partitioning::Neurons && options_.threads >= 2)
      throw Error(std::string("partitioning Neurons runs on one thread: ") + kNeuronsOnOneThread);
    const model::ModelPartition parts = model_.partition(
        options_.partitioning == Partitioning::Neurons ? model::PartitionGrain::Neurons : model::PartitionGrain::Joints);
    if (parts.size() > 1) return run_partitioned(model_, parts, options_, p_given, output_times, roots);
  }
  CommandSchedule schedule(model_, p_given, output_times.back(), sens_params);
  const std::vector<RootSpec> all_roots = schedule.roots(roots);

  CallbackData d;
  d.model = &model_;
  d.p = &schedule.p();
  d.eq = model_.make_whole();
  if (d.eq) d.eq->bind(d.p->data());
  if (ns == 0) compile_if_asked(d.eq.get(), options_);
  d.roots = &all_roots;
  d.sens_params = sens_params;
  d.n = model_.num_states();
  d.init_scratch(schedule.p());

  SundialsContext ctx;
  const std::vector<double> y0 = model_.initial_state(schedule.p());
  std::unique_ptr<IntegratorSession> session_owner;
  if (is_explicit_rk(options_.integrator) && ns == 0) {
    session_owner = make_explicit_session(ctx.get(), options_, y0.data(), d.n, rhs_cb, &d);
  } else {
    // Sensitivities run on CVODES BDF whatever integrator plain runs use (docs/sensitivity.md).
    SolverOptions cvodes_options = options_;
    if (is_explicit_rk(cvodes_options.integrator)) cvodes_options.integrator = IntegratorKind::Bdf;
    auto cv = std::make_unique<CvodesSession>(ctx.get(), cvodes_options, y0.data(), d.n, rhs_cb, &d);
    attach_linear_solver(*cv, d, model_, cvodes_options, y0, ns);
    if (ns > 0) init_sensitivities(*cv, model_, schedule.p(), sens_params);
    session_owner = std::move(cv);
  }
  IntegratorSession& session = *session_owner;
  if (!options_.atol_by_unit.empty()) {
    if (ns > 0) throw Error("[simulation] atol_by_unit applies to runs without sensitivities");
    std::vector<size_t> all(d.n);
    for (size_t i = 0; i < d.n; ++i) all[i] = i;
    session.set_state_atol(state_atol(model_, options_, all));
  }
  std::vector<int> dirs;
  for (const auto& r : all_roots) dirs.push_back(r.direction);
  session.init_roots(dirs, root_cb);
  session.set_stop_time(schedule.next_stop());

  SolveResult res;
  res.n_states = d.n;
  res.sens_params = sens_params;
  WholeSystem driver(model_, options_, schedule, session, d, output_times, roots.size(), res);
  ProgressLine progress(options_, schedule.t_end(), 1);
  run_loop(driver, schedule, progress);

  add_counters(res.stats, session.stats());
  res.stats.sens_rhs_evals = d.sens_evals;
  timer.stop(res.stats);
  return res;
}

}  // namespace phasmid::solver
