#include "solver/matrix_kernels.hpp"

#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#include <nvector/nvector_serial.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <utility>

namespace phasmid::solver {
namespace {

using Real = sunrealtype;
using Index = sunindextype;

// ---- dense (column-major, SM_COLUMN_D(A, j) is column j) ----

int dense_zero(SUNMatrix A) {
  std::fill(SM_DATA_D(A), SM_DATA_D(A) + SM_LDATA_D(A), 0.0);
  return SUNMAT_SUCCESS;
}

int dense_copy(SUNMatrix A, SUNMatrix B) {  // B = A
  if (SM_ROWS_D(A) != SM_ROWS_D(B) || SM_COLUMNS_D(A) != SM_COLUMNS_D(B)) return SUNMAT_ILL_INPUT;
  std::copy(SM_DATA_D(A), SM_DATA_D(A) + SM_LDATA_D(A), SM_DATA_D(B));
  return SUNMAT_SUCCESS;
}

int dense_scale_add_identity(Real c, SUNMatrix A) {  // A = c A + I
  const Index m = SM_ROWS_D(A), n = SM_COLUMNS_D(A);
  for (Index j = 0; j < n; ++j) {
    Real* col = SM_COLUMN_D(A, j);
    for (Index i = 0; i < m; ++i) col[i] *= c;
    if (j < m) col[j] += 1.0;
  }
  return SUNMAT_SUCCESS;
}

// LU with partial pivoting in place, the algorithm of SUNDlsMat_denseGETRF (row swaps across
// all columns, multipliers stored below the diagonal); last_flag = k + 1 at a zero pivot.
int dense_lu_setup(SUNLinearSolver S, SUNMatrix A) {
  auto* content = static_cast<SUNLinearSolverContent_Dense>(S->content);
  const Index n = SM_COLUMNS_D(A);
  Real** a = SM_COLS_D(A);
  Index* piv = content->pivots;
  for (Index k = 0; k < n; ++k) {
    Real* col_k = a[k];
    Index l = k;
    for (Index i = k + 1; i < n; ++i)
      if (std::abs(col_k[i]) > std::abs(col_k[l])) l = i;
    piv[k] = l;
    if (col_k[l] == 0.0) {
      content->last_flag = k + 1;
      return SUNLS_LUFACT_FAIL;
    }
    if (l != k)
      for (Index j = 0; j < n; ++j) std::swap(a[j][l], a[j][k]);
    const Real mult = 1.0 / col_k[k];
    for (Index i = k + 1; i < n; ++i) col_k[i] *= mult;
    for (Index j = k + 1; j < n; ++j) {
      Real* col_j = a[j];
      const Real a_kj = col_j[k];
      if (a_kj != 0.0) {
#pragma GCC ivdep
        for (Index i = k + 1; i < n; ++i) col_j[i] -= a_kj * col_k[i];
      }
    }
  }
  content->last_flag = 0;
  return SUNLS_SUCCESS;
}

// The solve for N <= kShortSolve unknowns (a joint network's stiff part has 12) with N known
// to the compiler: the substitutions unrolled, the unknowns in registers. The same operations
// in the same order as the general loops below, so the same results bit for bit; those spent
// most of a 12-unknown solve on loop set-up (1 240 instructions per solve).
constexpr Index kShortSolve = 16;
template <int N>
void lu_solve_short(Real* const* a, const Index* piv, Real* xd) {
  Real x[N > 0 ? N : 1];
  for (int k = 0; k < N; ++k) x[k] = xd[k];
  if constexpr (N > 1)  // (one unknown has no row to swap with)
    for (int k = 0; k < N; ++k)
      if (piv[k] != k) std::swap(x[k], x[piv[k]]);
#pragma GCC unroll 16
  for (int k = 0; k + 1 < N; ++k) {  // L y = P b, L unit lower triangular
    const Real* col = a[k];
#pragma GCC unroll 16
    for (int i = k + 1; i < N; ++i) x[i] -= col[i] * x[k];
  }
#pragma GCC unroll 16
  for (int k = N - 1; k >= 0; --k) {  // U x = y
    const Real* col = a[k];
    x[k] /= col[k];
#pragma GCC unroll 16
    for (int i = 0; i < k; ++i) x[i] -= col[i] * x[k];
  }
  for (int k = 0; k < N; ++k) xd[k] = x[k];
}

template <int... N>
constexpr std::array<void (*)(Real* const*, const Index*, Real*), sizeof...(N)> short_solves(
    std::integer_sequence<int, N...>) {
  return {&lu_solve_short<N>...};
}
constexpr auto kShortSolves = short_solves(std::make_integer_sequence<int, kShortSolve + 1>{});

// x = A^-1 b from the factors (SUNDlsMat_denseGETRS: the same operations in the same order,
// so the same numbers).
int dense_lu_solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, Real) {
  auto* content = static_cast<SUNLinearSolverContent_Dense>(S->content);
  const Index n = SM_COLUMNS_D(A);
  Real** a = SM_COLS_D(A);
  const Index* piv = content->pivots;
  Real* xd = NV_DATA_S(x);
  if (x != b) std::copy(NV_DATA_S(b), NV_DATA_S(b) + n, xd);
  if (n >= 1 && n <= kShortSolve) {
    kShortSolves[n](a, piv, xd);
    content->last_flag = SUNLS_SUCCESS;
    return SUNLS_SUCCESS;
  }
  for (Index k = 0; k < n; ++k)
    if (piv[k] != k) std::swap(xd[k], xd[piv[k]]);
  // Both substitutions carry the next unknown in a register (c): it is finished by one scalar
  // update before the vector update of the others, so that the chain from one unknown to the
  // next does not wait for that vector update to be stored and read back (the solve is a
  // large part of a BDF step on the rate models).
  Real c = xd[0];
  for (Index k = 0; k + 1 < n; ++k) {  // L y = P b, L unit lower triangular
    const Real* col_k = a[k];
    const Real yk = c;
    xd[k] = yk;
    c = xd[k + 1] - col_k[k + 1] * yk;
    for (Index i = k + 2; i < n; ++i) xd[i] -= col_k[i] * yk;
  }
  for (Index k = n - 1; k > 0; --k) {  // U x = y
    const Real* col_k = a[k];
    const Real xk = c / col_k[k];
    xd[k] = xk;
    c = xd[k - 1] - col_k[k - 1] * xk;
    for (Index i = 0; i + 1 < k; ++i) xd[i] -= col_k[i] * xk;
  }
  xd[0] = c / a[0][0];
  content->last_flag = SUNLS_SUCCESS;
  return SUNLS_SUCCESS;
}

// ---- sparse (CSC or CSR; "major" = columns for CSC, rows for CSR) ----

int sparse_zero(SUNMatrix A) {
  std::fill(SM_DATA_S(A), SM_DATA_S(A) + SM_NNZ_S(A), 0.0);
  std::fill(SM_INDEXVALS_S(A), SM_INDEXVALS_S(A) + SM_NNZ_S(A), Index(0));
  std::fill(SM_INDEXPTRS_S(A), SM_INDEXPTRS_S(A) + SM_NP_S(A) + 1, Index(0));
  return SUNMAT_SUCCESS;
}

int sparse_copy(SUNMatrix A, SUNMatrix B) {  // B = A
  const Index nnz = SM_INDEXPTRS_S(A)[SM_NP_S(A)];
  if (SM_SPARSETYPE_S(A) != SM_SPARSETYPE_S(B) || SM_ROWS_S(A) != SM_ROWS_S(B) ||
      SM_COLUMNS_S(A) != SM_COLUMNS_S(B) || SM_NNZ_S(B) < nnz)
    return SUNMatCopy_Sparse(A, B);  // reallocates B
  sparse_zero(B);
  std::copy(SM_DATA_S(A), SM_DATA_S(A) + nnz, SM_DATA_S(B));
  std::copy(SM_INDEXVALS_S(A), SM_INDEXVALS_S(A) + nnz, SM_INDEXVALS_S(B));
  std::copy(SM_INDEXPTRS_S(A), SM_INDEXPTRS_S(A) + SM_NP_S(A) + 1, SM_INDEXPTRS_S(B));
  return SUNMAT_SUCCESS;
}

int sparse_scale_add_identity(Real c, SUNMatrix A) {  // A = c A + I
  const Index np = SM_NP_S(A);
  const Index* ptr = SM_INDEXPTRS_S(A);
  const Index* idx = SM_INDEXVALS_S(A);
  // Fast path only when every diagonal entry is in the pattern; otherwise SUNDIALS'
  // routine inserts the missing ones (and reallocates).
  const Index ndiag = std::min(SM_ROWS_S(A), SM_COLUMNS_S(A));
  for (Index j = 0; j < ndiag; ++j) {
    bool found = false;
    for (Index k = ptr[j]; k < ptr[j + 1] && !found; ++k) found = idx[k] == j;
    if (!found) return SUNMatScaleAddI_Sparse(c, A);
  }
  Real* v = SM_DATA_S(A);
  for (Index k = 0, nnz = ptr[np]; k < nnz; ++k) v[k] *= c;
  for (Index j = 0; j < ndiag; ++j)
    for (Index k = ptr[j]; k < ptr[j + 1]; ++k)
      if (idx[k] == j) {
        v[k] += 1.0;
        break;
      }
  return SUNMAT_SUCCESS;
}

void install_dense_matrix_ops(SUNMatrix A);
void install_sparse_matrix_ops(SUNMatrix A);

// CVODES keeps a clone of the Jacobian (cvLs savedJ) and copies it back into the Newton
// matrix at every setup without a new Jacobian: clones get the kernels too.
SUNMatrix dense_clone(SUNMatrix A) {
  SUNMatrix B = SUNMatClone_Dense(A);
  if (B) install_dense_matrix_ops(B);
  return B;
}

SUNMatrix sparse_clone(SUNMatrix A) {
  SUNMatrix B = SUNMatClone_Sparse(A);
  if (B) install_sparse_matrix_ops(B);
  return B;
}

void install_dense_matrix_ops(SUNMatrix A) {
  A->ops->clone = dense_clone;
  A->ops->zero = dense_zero;
  A->ops->copy = dense_copy;
  A->ops->scaleaddi = dense_scale_add_identity;
}

void install_sparse_matrix_ops(SUNMatrix A) {
  A->ops->clone = sparse_clone;
  A->ops->zero = sparse_zero;
  A->ops->copy = sparse_copy;
  A->ops->scaleaddi = sparse_scale_add_identity;
}

}  // namespace

void install_dense_kernels(SUNMatrix A, SUNLinearSolver ls) {
  if (SUNMatGetID(A) != SUNMATRIX_DENSE) return;
  install_dense_matrix_ops(A);
  if (ls && SUNLinSolGetID(ls) == SUNLINEARSOLVER_DENSE) {
    ls->ops->setup = dense_lu_setup;
    ls->ops->solve = dense_lu_solve;
  }
}

void install_sparse_kernels(SUNMatrix A) {
  if (SUNMatGetID(A) != SUNMATRIX_SPARSE) return;
  install_sparse_matrix_ops(A);
}

}  // namespace phasmid::solver
