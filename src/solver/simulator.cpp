#include "solver/simulator.hpp"

#include <cvodes/cvodes.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>
#include <sunmatrix/sunmatrix_band.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

#include "common/error.hpp"
#include "solver/cvodes_counters.hpp"
#include "solver/cvodes_setup.hpp"
#include "solver/matrix_kernels.hpp"
#include "solver/partitioned_simulator.hpp"
#include "solver/serial_kernels.hpp"
#include "solver/trigger_tracker.hpp"

namespace phasmid::solver {
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
  d->model->rhs(t, N_VGetArrayPointer(y), d->p->data(), N_VGetArrayPointer(ydot));
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

// RAII for the SUNDIALS objects of one run.
struct CvodeHandles {
  SUNContext ctx = nullptr;
  void* mem = nullptr;
  N_Vector y = nullptr;
  N_Vector* yS = nullptr;
  int ns = 0;
  SUNMatrix A = nullptr;
  SUNLinearSolver LS = nullptr;
  SUNNonlinearSolver NLS = nullptr;
  SUNNonlinearSolver NLS_sens = nullptr;
  ~CvodeHandles() {
    if (NLS_sens) SUNNonlinSolFree(NLS_sens);
    if (NLS) SUNNonlinSolFree(NLS);
    if (mem) CVodeFree(&mem);
    if (LS) SUNLinSolFree(LS);
    if (A) SUNMatDestroy(A);
    if (yS) N_VDestroyVectorArray(yS, ns);
    if (y) N_VDestroy(y);
    if (ctx) SUNContext_Free(&ctx);
  }
};

}  // namespace

Simulator::Simulator(const OdeModel& model, SolverOptions options) : model_(model), options_(options) {}

std::vector<double> output_grid(double t_end, double dt) {
  if (!(dt > 0) || !(t_end > 0)) throw Error("output grid needs t_end > 0 and dt > 0");
  std::vector<double> t;
  size_t n = static_cast<size_t>(std::floor(t_end / dt + 1e-9));
  for (size_t k = 0; k <= n; ++k) t.push_back(k * dt);
  if (t_end - t.back() > 1e-9) t.push_back(t_end);
  return t;
}

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

SolveResult Simulator::run(const std::vector<double>& p_given, const std::vector<double>& output_times,
                           const std::vector<RootSpec>& roots, const std::vector<size_t>& sens_params) const {
  auto wall0 = std::chrono::steady_clock::now();
  const size_t n = model_.num_states();
  if (p_given.size() != model_.parameters().size()) throw Error("internal: parameter vector size mismatch");
  if (output_times.empty() || output_times.front() < 0) throw Error("output times must start at t >= 0");
  const size_t ns = sens_params.size();
  const std::vector<model::CommandTrigger>& triggers = model_.triggers();
  const bool partition = options_.partitioning == Partitioning::On ||
                         (options_.partitioning == Partitioning::Auto && model_.partition_by_default());
  if (partition && ns == 0) {
    const model::ModelPartition parts = model_.partition();
    if (parts.size() > 1) return run_partitioned(model_, parts, options_, p_given, output_times, roots);
  }
  // A command time set by a trigger is a function of the other parameters (the event time plus
  // a constant delay), not a free parameter: there is no sensitivity to it.
  for (const auto& tr : triggers)
    for (size_t q : tr.targets)
      if (std::find(sens_params.begin(), sens_params.end(), q) != sens_params.end())
        throw Error("no sensitivity to " + model_.parameters().at(q).name + ": it is set by the [[triggers]] event " +
                    tr.event + " (give it a fixed value to differentiate by it)");
  // Triggered command times are written into this copy when their events occur; until then
  // they are "never" (no breakpoint, command off).
  std::vector<double> p = p_given;
  for (const auto& tr : triggers)
    for (size_t k : tr.targets) p[k] = model::kUnresolvedMs;
  // Each trigger watches its own threshold crossing, after the caller's roots (whose indices
  // in SolveResult::events stay as given); crossings in both directions, for the debounce.
  std::vector<RootSpec> all_roots = roots;
  for (const auto& tr : triggers) all_roots.push_back({tr.state, tr.level_scale * p[tr.level_param], 0});

  CallbackData d;
  d.model = &model_;
  d.p = &p;
  d.roots = &all_roots;
  d.sens_params = sens_params;
  d.n = n;
  d.init_scratch(p);

  CvodeHandles h;
  check_cvodes(SUNContext_Create(nullptr, &h.ctx), "SUNContext_Create");
  h.y = N_VNew_Serial(n, h.ctx);
  // Clones (CVODES' work vectors, the sensitivity arrays) copy the ops table.
  if (options_.vector_kernels == VectorKernels::Phasmid) install_serial_kernels(h.y);
  std::vector<double> y0 = model_.initial_state(p);
  for (size_t i = 0; i < n; ++i) NV_Ith_S(h.y, i) = y0[i];
  const bool adams = options_.integrator == IntegratorKind::Adams;
  h.mem = CVodeCreate(adams ? CV_ADAMS : CV_BDF, h.ctx);
  if (!h.mem) throw SolverError("CVodeCreate failed");
  const double t0 = 0.0;
  check_cvodes(CVodeInit(h.mem, rhs_cb, t0, h.y), "CVodeInit");
  check_cvodes(CVodeSStolerances(h.mem, options_.rtol, options_.atol), "CVodeSStolerances");
  check_cvodes(CVodeSetUserData(h.mem, &d), "CVodeSetUserData");
  apply_step_options(h.mem, options_);

  int bw = model_.jacobian_half_bandwidth();
  bool band = options_.linear_solver == LinearSolverKind::Band && bw >= 0;
  // KLU needs an exact Jacobian function (a difference quotient is only available for dense/band).
  const bool want_klu = options_.linear_solver == LinearSolverKind::Klu ||
                        (options_.linear_solver == LinearSolverKind::Auto &&
                         n > (ns > 0 ? kDenseMaxStatesWithSensitivities : kDenseMaxStates));
  const bool klu = want_klu && options_.jacobian == JacobianKind::AutoDiff;
  if (adams) {
    h.NLS = SUNNonlinSol_FixedPoint(h.y, 0, h.ctx);
    check_cvodes(CVodeSetNonlinearSolver(h.mem, h.NLS), "CVodeSetNonlinearSolver");
  } else if (band) {
    h.A = SUNBandMatrix(n, bw, bw, h.ctx);
    h.LS = SUNLinSol_Band(h.y, h.A, h.ctx);
  } else if (klu) {
    sparsity_pattern(&d, y0);
    h.A = SUNSparseMatrix(n, n, static_cast<sunindextype>(d.row_idx.size()), CSC_MAT, h.ctx);
    h.LS = SUNLinSol_KLU(h.y, h.A, h.ctx);
  } else {
    h.A = SUNDenseMatrix(n, n, h.ctx);
    h.LS = SUNLinSol_Dense(h.y, h.A, h.ctx);
  }
  if (options_.vector_kernels == VectorKernels::Phasmid && h.A) {
    if (klu) install_sparse_kernels(h.A);
    else if (!band) install_dense_kernels(h.A, h.LS);
  }
  if (!adams) check_cvodes(CVodeSetLinearSolver(h.mem, h.LS, h.A), "CVodeSetLinearSolver");
  if (!adams && options_.jacobian == JacobianKind::AutoDiff)
    check_cvodes(CVodeSetJacFn(h.mem, klu ? jac_sparse_cb : band ? jac_band_cb : jac_dense_cb), "CVodeSetJacFn");

  if (ns > 0) {
    h.ns = static_cast<int>(ns);
    h.yS = N_VCloneVectorArray(h.ns, h.y);
    // s(0) = dy0/dp: initial states are algebraic (at most linear) functions of the
    // parameters (e.g. initial joint angles), so a central difference is exact.
    for (int j = 0; j < h.ns; ++j) {
      size_t k = sens_params[j];
      double hstep = 1e-6 * std::max(1.0, std::abs(p[k]));
      std::vector<double> pp = p, pm = p;
      pp[k] += hstep;
      pm[k] -= hstep;
      std::vector<double> yp = model_.initial_state(pp), ym = model_.initial_state(pm);
      for (size_t i = 0; i < n; ++i) NV_Ith_S(h.yS[j], i) = (yp[i] - ym[i]) / (2 * hstep);
    }
    int method = options_.sensitivity_method == SensitivityMethod::Staggered ? CV_STAGGERED : CV_SIMULTANEOUS;
    if (options_.sensitivity_rhs == SensitivityRhs::Batched && ns > 1)
      check_cvodes(CVodeSensInit(h.mem, h.ns, method, sens_rhs_batched_cb, h.yS), "CVodeSensInit");
    else
      check_cvodes(CVodeSensInit1(h.mem, h.ns, method, sens_rhs_cb, h.yS), "CVodeSensInit1");
    if (adams) {
      h.NLS_sens = method == CV_STAGGERED ? SUNNonlinSol_FixedPointSens(h.ns + 1, h.y, 0, h.ctx)
                                          : SUNNonlinSol_FixedPointSens(h.ns + 1, h.y, 0, h.ctx);
      if (method == CV_STAGGERED) check_cvodes(CVodeSetNonlinearSolverSensStg(h.mem, h.NLS_sens), "CVodeSetNonlinearSolverSensStg");
      else check_cvodes(CVodeSetNonlinearSolverSensSim(h.mem, h.NLS_sens), "CVodeSetNonlinearSolverSensSim");
    }
    std::vector<double> pbar(ns);
    for (size_t j = 0; j < ns; ++j) pbar[j] = std::abs(p[sens_params[j]]) > 0 ? std::abs(p[sens_params[j]]) : 1.0;
    check_cvodes(CVodeSetSensParams(h.mem, nullptr, pbar.data(), nullptr), "CVodeSetSensParams");
    if (!options_.sensitivity_atol_scale.empty()) {
      if (options_.sensitivity_atol_scale.size() != n) throw Error("internal: sensitivity_atol_scale size mismatch");
      const double f = options_.sensitivity_tolerance_factor;
      N_Vector* atolS = N_VCloneVectorArray(h.ns, h.y);
      for (int j = 0; j < h.ns; ++j)
        for (size_t i = 0; i < n; ++i) NV_Ith_S(atolS[j], i) = f * options_.atol / pbar[j] * options_.sensitivity_atol_scale[i];
      const int flag = CVodeSensSVtolerances(h.mem, f * options_.rtol, atolS);
      N_VDestroyVectorArray(atolS, h.ns);
      check_cvodes(flag, "CVodeSensSVtolerances");
    } else if (options_.sensitivity_tolerance_factor == 1.0) {
      check_cvodes(CVodeSensEEtolerances(h.mem), "CVodeSensEEtolerances");
    } else {
      const double f = options_.sensitivity_tolerance_factor;
      std::vector<double> atolS(ns);
      for (size_t j = 0; j < ns; ++j) atolS[j] = f * options_.atol / pbar[j];
      check_cvodes(CVodeSensSStolerances(h.mem, f * options_.rtol, atolS.data()), "CVodeSensSStolerances");
    }
    check_cvodes(CVodeSetSensErrCon(h.mem, options_.sensitivity_error_control ? SUNTRUE : SUNFALSE), "CVodeSetSensErrCon");
  }
  std::vector<int> dirs;
  for (auto& r : all_roots) dirs.push_back(r.direction);
  if (!all_roots.empty()) {
    check_cvodes(CVodeRootInit(h.mem, static_cast<int>(all_roots.size()), root_cb), "CVodeRootInit");
    check_cvodes(CVodeSetRootDirection(h.mem, dirs.data()), "CVodeSetRootDirection");
    CVodeSetNoInactiveRootWarn(h.mem);
  }

  const double t_end = output_times.back();
  std::vector<double> breaks = model_.breakpoints(p, t_end);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::remove_if(breaks.begin(), breaks.end(), [&](double b) { return b <= t0 || b >= t_end; }),
               breaks.end());
  breaks.push_back(t_end);
  size_t next_break = 0;
  // dtau_k/dp_j of each breakpoint: switch times are algebraic functions of the parameters
  // (command times, switching periods), so central differences are exact; matched by value.
  std::vector<std::vector<double>> dtau(breaks.size(), std::vector<double>(ns, 0.0));
  for (size_t j = 0; j < ns; ++j) {
    size_t k = sens_params[j];
    double hstep = 1e-6 * std::max(1.0, std::abs(p[k]));
    std::vector<double> pp = p, pm = p;
    pp[k] += hstep;
    pm[k] -= hstep;
    std::vector<double> bp = model_.breakpoints(pp, t_end), bm = model_.breakpoints(pm, t_end);
    std::sort(bp.begin(), bp.end());
    std::sort(bm.begin(), bm.end());
    auto nearest = [](const std::vector<double>& v, double x) {
      double best = NAN;
      for (double b : v)
        if (std::isnan(best) || std::abs(b - x) < std::abs(best - x)) best = b;
      return best;
    };
    for (size_t b = 0; b + 1 < breaks.size(); ++b) {
      // The perturbed switch nearest to the nominal one is the same switch as long as it
      // moved by less than a quarter of the gap to the neighbouring switches.
      double gap = breaks[b + 1] - breaks[b];
      if (b > 0) gap = std::min(gap, breaks[b] - breaks[b - 1]);
      double up = nearest(bp, breaks[b]), dn = nearest(bm, breaks[b]);
      if (std::abs(up - breaks[b]) > 0.25 * gap || std::abs(dn - breaks[b]) > 0.25 * gap) continue;
      dtau[b][j] = (up - dn) / (2 * hstep);
    }
  }
  std::vector<double> f_before(n), f_after(n);
  // The state is continuous at a switch; if the switch time moves with p_j the sensitivity
  // jumps: s(tau+) = s(tau-) + (f(tau-) - f(tau+)) dtau/dp_j.
  auto apply_jump = [&](double tau, const std::vector<double>& dtau_dp) {
    if (std::all_of(dtau_dp.begin(), dtau_dp.end(), [](double v) { return v == 0.0; })) return;
    const double* yv = N_VGetArrayPointer(h.y);
    const double delta = 1e-9 * std::max(1.0, std::abs(tau));  // one-sided limits at the switch
    model_.rhs(tau - delta, yv, p.data(), f_before.data());
    model_.rhs(tau + delta, yv, p.data(), f_after.data());
    for (size_t j = 0; j < ns; ++j)
      if (dtau_dp[j] != 0.0)
        for (size_t i = 0; i < n; ++i) NV_Ith_S(h.yS[j], i) += (f_before[i] - f_after[i]) * dtau_dp[j];
  };
  std::vector<double> dtau_now(ns, 0.0);  // d tau / dp of commands triggered at the current event
  check_cvodes(CVodeSetStopTime(h.mem, breaks[0]), "CVodeSetStopTime");

  SolveResult res;
  res.n_states = n;
  res.sens_params = sens_params;
  std::vector<int> rootsfound(all_roots.size());
  std::vector<TriggerTracker> trig(triggers.size());
  const bool show_progress = options_.progress && isatty(STDERR_FILENO);
  auto last_print = std::chrono::steady_clock::now();
  std::vector<double> ydot(n);

  long steps_before_restarts = 0;  // CVodeReInit resets the step counter
  // Adds CVODES' counters since the last (re)start to the run's statistics.
  auto accumulate_counters = [&] { add_cvodes_counters(h.mem, res.stats); };
  auto total_steps = [&] {
    long v = 0;
    CVodeGetNumSteps(h.mem, &v);
    return steps_before_restarts + v;
  };
  double t_sens = 0.0;
  auto record_output = [&](double t, bool fetch_sens) {
    res.t.push_back(t);
    res.steps_at_output.push_back(total_steps());
    for (size_t i = 0; i < n; ++i) res.y.push_back(NV_Ith_S(h.y, i));
    if (ns && options_.sensitivities_at_outputs) {
      if (fetch_sens) check_cvodes(CVodeGetSens(h.mem, &t_sens, h.yS), "CVodeGetSens");
      for (size_t i = 0; i < n; ++i)
        for (size_t j = 0; j < ns; ++j) res.s.push_back(NV_Ith_S(h.yS[j], i));
    }
  };

  double t = t0;
  size_t k_out = 0;
  if (output_times[0] <= t0) {
    record_output(t0, false);
    k_out = 1;
  }
  while (k_out < output_times.size()) {
    double tout = output_times[k_out];
    int flag = CVode(h.mem, tout, h.y, &t, CV_NORMAL);
    if (flag < 0) {
      std::ostringstream os;
      os << "CVODES failed at t = " << t << " ms: " << CVodeGetReturnFlagName(flag)
         << " (try --set on the offending parameter, or tighter tolerances)";
      throw SolverError(os.str());
    }
    // Sensitivities are needed at events, at restarts and (if kept) at output times
    // (record_output fetches those).
    if (ns && (flag == CV_ROOT_RETURN || flag == CV_TSTOP_RETURN)) check_cvodes(CVodeGetSens(h.mem, &t, h.yS), "CVodeGetSens");
    bool restart_now = false;
    std::fill(dtau_now.begin(), dtau_now.end(), 0.0);
    if (flag == CV_ROOT_RETURN) {
      check_cvodes(CVodeGetRootInfo(h.mem, rootsfound.data()), "CVodeGetRootInfo");
      model_.rhs(t, N_VGetArrayPointer(h.y), p.data(), ydot.data());
      for (size_t k = 0; k < triggers.size(); ++k) {
        const int dir = rootsfound[roots.size() + k];
        if (!dir) continue;
        const model::CommandTrigger& tr = triggers[k];
        if (!trig[k].fires(tr, t, dir, p, N_VGetArrayPointer(h.y))) continue;
        const double when = t + tr.delay_ms;
        // d t_event / dp_j by the implicit-function theorem on g = y[state] - scale p[level]:
        // -(s_state,j - scale [p_j is the level]) / f_state (dg/dt = 0); the delay is constant,
        // so d tau / dp = d t_event / dp (a jump at tau, below: at once or at the added breakpoint).
        std::vector<double> dte(ns, 0.0);
        if (ns) {
          const double gdot = ydot[tr.state];
          if (gdot == 0.0 || !std::isfinite(gdot))
            throw Error("trigger " + tr.event + " at t = " + std::to_string(t) +
                        " ms is a tangential crossing: its time is not differentiable");
          for (size_t j = 0; j < ns; ++j)
            dte[j] = -(NV_Ith_S(h.yS[j], tr.state) - (sens_params[j] == tr.level_param ? tr.level_scale : 0.0)) / gdot;
        }
        for (size_t q : tr.targets) {
          p[q] = when;
          d.set_parameter(q, when);
          res.commands.push_back({q, when, k});
        }
        // Two commands switching at one time with different d tau / dp have no single jump.
        auto merge_dtau = [&](std::vector<double>& into) {
          for (size_t j = 0; j < ns; ++j) {
            if (into[j] != 0.0 && std::abs(into[j] - dte[j]) > 1e-9 * std::max(1.0, std::abs(dte[j])))
              throw Error("trigger " + tr.event + ": its command time coincides with another switch that moves "
                          "differently with " + model_.parameters().at(sens_params[j]).name +
                          " (no single sensitivity jump)");
            into[j] = dte[j];
          }
        };
        if (when <= t + 1e-9 * std::max(1.0, std::abs(t))) {
          // The jump is applied after this event's sensitivities are recorded (they are s(t-)).
          restart_now = true;
          merge_dtau(dtau_now);
        } else if (when < t_end) {
          // A later command: one more breakpoint. The sensitivity is continuous at the event;
          // it jumps at tau with d tau / dp = d t_event / dp found here.
          auto at = std::upper_bound(breaks.begin() + static_cast<long>(next_break), breaks.end() - 1, when);
          const size_t b = static_cast<size_t>(at - breaks.begin());
          if (!(b > next_break && std::abs(breaks[b - 1] - when) < 1e-9)) {  // not already a breakpoint
            breaks.insert(at, when);
            dtau.insert(dtau.begin() + static_cast<long>(b), std::vector<double>(ns, 0.0));
            merge_dtau(dtau[b]);
            check_cvodes(CVodeSetStopTime(h.mem, breaks[next_break]), "CVodeSetStopTime");
          } else {
            merge_dtau(dtau[b - 1]);
          }
        }
      }
      for (size_t r = 0; r < roots.size(); ++r) {
        if (!rootsfound[r]) continue;
        Event e;
        e.t = t;
        e.root = r;
        e.direction = rootsfound[r];
        e.y.assign(N_VGetArrayPointer(h.y), N_VGetArrayPointer(h.y) + n);
        e.ydot = ydot;
        if (ns) {
          e.s.resize(n * ns);
          for (size_t i = 0; i < n; ++i)
            for (size_t j = 0; j < ns; ++j) e.s[i * ns + j] = NV_Ith_S(h.yS[j], i);
        }
        res.events.push_back(std::move(e));
      }
    }
    if (restart_now) {
      // A trigger set a command time to this very event: the right-hand side changes here.
      steps_before_restarts = total_steps();
      accumulate_counters();
      check_cvodes(CVodeReInit(h.mem, t, h.y), "CVodeReInit");
      if (ns) {
        // The command switches at the event itself: s(t+) = s(t-) + (f(t-) - f(t+)) d t_event / dp.
        apply_jump(t, dtau_now);
        // Also needed without a jump: at a root return CVODES' own sensitivities are at its
        // internal time beyond the root, the ones fetched above at the root.
        check_cvodes(CVodeSensReInit(h.mem, options_.sensitivity_method == SensitivityMethod::Staggered ? CV_STAGGERED : CV_SIMULTANEOUS, h.yS), "CVodeSensReInit");
      }
      ++res.stats.restarts;
    }
    if (flag == CV_TSTOP_RETURN && next_break + 1 < breaks.size() && std::abs(t - breaks[next_break]) < 1e-9) {
      // The right-hand side changes here: restart the integrator from the current state.
      // Sensitivities carry over, plus a jump if the switch time moves with p (below).
      steps_before_restarts = total_steps();
      accumulate_counters();
      check_cvodes(CVodeReInit(h.mem, t, h.y), "CVodeReInit");
      if (ns) apply_jump(t, dtau[next_break]);
      if (ns) check_cvodes(CVodeSensReInit(h.mem, options_.sensitivity_method == SensitivityMethod::Staggered ? CV_STAGGERED : CV_SIMULTANEOUS, h.yS), "CVodeSensReInit");
      ++next_break;
      check_cvodes(CVodeSetStopTime(h.mem, breaks[next_break]), "CVodeSetStopTime");
      ++res.stats.restarts;
    }
    if (std::abs(t - tout) < 1e-9 * std::max(1.0, std::abs(tout))) {
      record_output(tout, flag == CV_SUCCESS);  // events and restarts fetched them already
      ++k_out;
    }
    if (show_progress) {
      auto now = std::chrono::steady_clock::now();
      if (now - last_print > std::chrono::milliseconds(200)) {
        std::fprintf(stderr, "\r%s: t = %.0f / %.0f ms (%3.0f%%)", options_.progress_label.c_str(), t, t_end,
                     100.0 * t / t_end);
        last_print = now;
      }
    }
  }
  if (show_progress) std::fprintf(stderr, "\r%s: t = %.0f / %.0f ms (100%%)\n", options_.progress_label.c_str(), t_end, t_end);

  res.stats.steps = total_steps();
  accumulate_counters();
  res.stats.sens_rhs_evals = d.sens_evals;
  res.stats.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return res;
}

}  // namespace phasmid::solver
