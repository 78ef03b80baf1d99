#include "solver/callback_data.hpp"

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_band.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "solver/command_schedule.hpp"
#include "solver/simulator.hpp"

namespace phasmid::solver::whole_system {

using model::Jet1;
using model::Jet4;
using model::JetK;
using model::kJacobianChunk;
using model::OdeModel;

int rhs_cb(sunrealtype t, N_Vector y, N_Vector ydot, void* ud) {
  auto* d = static_cast<CallbackData*>(ud);
  if (d->eq) d->eq->rhs(t, N_VGetArrayPointer(y), d->p->data(), N_VGetArrayPointer(ydot));
  else d->model->rhs(t, N_VGetArrayPointer(y), d->p->data(), N_VGetArrayPointer(ydot));
  for (size_t i = 0; i < d->n; ++i)
    if (!std::isfinite(NV_Ith_S(ydot, i))) return 1;  // recoverable: CVODES retries a smaller step
  return 0;
}

namespace {

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

CallbackData jacobian_data(const OdeModel& model, const std::vector<double>& p) {
  CallbackData d;
  d.model = &model;
  d.p = &p;
  d.n = model.num_states();
  d.jK.init(d.n, p);
  return d;
}

}  // namespace

int root_cb(sunrealtype, N_Vector y, sunrealtype* g, void* ud) {
  auto* d = static_cast<CallbackData*>(ud);
  const auto& roots = *d->roots;
  for (size_t r = 0; r < roots.size(); ++r) g[r] = NV_Ith_S(y, roots[r].state) - roots[r].level;
  return 0;
}

void attach_linear_solver(CvodesSession& session, CallbackData& d, const OdeModel& model,
                          const SolverOptions& options, const std::vector<double>& y0, size_t ns) {
  const int bw = model.jacobian_half_bandwidth();
  const bool band = options.linear_solver == LinearSolverKind::Band && bw >= 0;
  const bool klu = options.linear_solver == LinearSolverKind::Klu ||
                   (options.linear_solver == LinearSolverKind::Auto &&
                    d.n > (ns > 0 ? kDenseMaxStatesWithSensitivities : kDenseMaxStates));
  if (klu) sparsity_pattern(&d, y0);
  const LinearSystem kind = band ? LinearSystem::Band : klu ? LinearSystem::Sparse : LinearSystem::Dense;
  CVLsJacFn jac = band ? jac_band_cb : klu ? jac_sparse_cb : jac_dense_cb;
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

}  // namespace phasmid::solver::whole_system

namespace phasmid::solver {

using whole_system::CallbackData;
using whole_system::fill_jacobian;
using whole_system::fill_sparse_jacobian;
using whole_system::jacobian_data;
using whole_system::sparsity_pattern;

std::vector<double> jacobian_autodiff(const model::OdeModel& model, double t, const std::vector<double>& y,
                                      const std::vector<double>& p) {
  CallbackData d = jacobian_data(model, p);
  std::vector<double> J(d.n * d.n);
  fill_jacobian(&d, t, y.data(), J.data());
  return J;
}

std::vector<double> jacobian_sparse_autodiff(const model::OdeModel& model, double t, const std::vector<double>& y,
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

}  // namespace phasmid::solver
