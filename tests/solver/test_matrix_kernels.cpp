// phasmid's compiled matrix kernels and dense LU (solver/matrix_kernels.hpp) against
// SUNDIALS' own dense and sparse implementations.
#include <gtest/gtest.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <cmath>
#include <random>
#include <string>

#include "solver/matrix_kernels.hpp"

namespace {

using namespace phasmid::solver;

class KernelFixture {
 protected:
  explicit KernelFixture(sunindextype n) : kN(n) { SUNContext_Create(nullptr, &ctx_); }
  ~KernelFixture() { SUNContext_Free(&ctx_); }
  // A random matrix, diagonal kept small so that partial pivoting swaps rows.
  void fill(SUNMatrix A) const {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (sunindextype j = 0; j < kN; ++j)
      for (sunindextype i = 0; i < kN; ++i) SM_ELEMENT_D(A, i, j) = i == j ? 0.01 * u(rng) : u(rng);
  }
  const sunindextype kN;
  SUNContext ctx_ = nullptr;
};

// Dense: sizes of the unrolled solves (up to 16 unknowns) and of the general loops above them.
class MatrixKernels : public KernelFixture, public ::testing::TestWithParam<int> {
 protected:
  MatrixKernels() : KernelFixture(GetParam()) {}
};

class SparseKernels : public KernelFixture, public ::testing::Test {
 protected:
  SparseKernels() : KernelFixture(13) {}
};

TEST_P(MatrixKernels, DenseLuSolveMatchesSundialsAndSolvesTheSystem) {
  N_Vector y = N_VNew_Serial(kN, ctx_);
  SUNMatrix A0 = SUNDenseMatrix(kN, kN, ctx_), A1 = SUNDenseMatrix(kN, kN, ctx_), M = SUNDenseMatrix(kN, kN, ctx_);
  fill(A0);
  fill(A1);
  fill(M);
  SUNLinearSolver S0 = SUNLinSol_Dense(y, A0, ctx_), S1 = SUNLinSol_Dense(y, A1, ctx_);
  install_dense_kernels(A1, S1);
  // M = c M + I through the installed ops matches the library's
  SUNMatrix M1 = SUNMatClone(A1);  // a clone carries the kernels
  ASSERT_EQ(SUNMatCopy(M, M1), 0);
  ASSERT_EQ(SUNMatScaleAddI(-0.3, M1), 0);
  ASSERT_EQ(SUNMatScaleAddI(-0.3, M), 0);
  for (sunindextype j = 0; j < kN; ++j)
    for (sunindextype i = 0; i < kN; ++i) EXPECT_DOUBLE_EQ(SM_ELEMENT_D(M, i, j), SM_ELEMENT_D(M1, i, j));
  ASSERT_EQ(SUNMatCopy(M1, A1), 0);  // the clone's copy (savedJ -> A in CVODES)
  ASSERT_EQ(SUNMatCopy(M, A0), 0);
  ASSERT_EQ(SUNLinSolSetup(S0, A0), 0);
  ASSERT_EQ(SUNLinSolSetup(S1, A1), 0);
  N_Vector b = N_VNew_Serial(kN, ctx_), x0 = N_VNew_Serial(kN, ctx_), x1 = N_VNew_Serial(kN, ctx_);
  for (sunindextype i = 0; i < kN; ++i) NV_Ith_S(b, i) = std::sin(1.0 + i);
  ASSERT_EQ(SUNLinSolSolve(S0, A0, x0, b, 0.0), 0);
  ASSERT_EQ(SUNLinSolSolve(S1, A1, x1, b, 0.0), 0);
  for (sunindextype i = 0; i < kN; ++i) {
    EXPECT_NEAR(NV_Ith_S(x0, i), NV_Ith_S(x1, i), 1e-12 * (1 + std::abs(NV_Ith_S(x0, i))));
    double r = -NV_Ith_S(b, i);  // residual of the original system M x = b
    for (sunindextype j = 0; j < kN; ++j) r += SM_ELEMENT_D(M, i, j) * NV_Ith_S(x1, j);
    EXPECT_NEAR(r, 0.0, 1e-10);
  }
  // A zero pivot is reported as a recoverable failure, like SUNLinSol_Dense.
  ASSERT_EQ(SUNMatZero(A1), 0);
  EXPECT_EQ(SUNLinSolSetup(S1, A1), SUNLS_LUFACT_FAIL);
  for (N_Vector v : {y, b, x0, x1}) N_VDestroy(v);
  for (SUNMatrix m : {A0, A1, M, M1}) SUNMatDestroy(m);
  SUNLinSolFree(S0);
  SUNLinSolFree(S1);
}

TEST_F(SparseKernels, ScaleAddIdentityAndCopyMatchSundials) {
  SUNMatrix D = SUNDenseMatrix(kN, kN, ctx_);
  fill(D);
  for (sunindextype j = 0; j < kN; ++j)  // sparsify
    for (sunindextype i = 0; i < kN; ++i)
      if ((i + 2 * j) % 3 == 0 && i != j) SM_ELEMENT_D(D, i, j) = 0.0;
  for (bool missing_diagonal : {false, true}) {
    if (missing_diagonal) SM_ELEMENT_D(D, 4, 4) = 0.0;  // forces the library's reallocating path
    SUNMatrix A0 = SUNSparseFromDenseMatrix(D, 0.0, CSC_MAT), A1 = SUNSparseFromDenseMatrix(D, 0.0, CSC_MAT);
    install_sparse_kernels(A1);
    SUNMatrix B1 = SUNMatClone(A1);
    ASSERT_EQ(SUNMatCopy(A1, B1), 0);
    ASSERT_EQ(SUNMatScaleAddI(-0.7, B1), 0);
    ASSERT_EQ(SUNMatScaleAddI(-0.7, A0), 0);
    SUNMatrix R0 = SUNDenseMatrix(kN, kN, ctx_), R1 = SUNDenseMatrix(kN, kN, ctx_);
    // dense views of both for comparison
    SUNMatZero(R0);
    SUNMatZero(R1);
    for (sunindextype j = 0; j < kN; ++j) {
      for (sunindextype k = SM_INDEXPTRS_S(A0)[j]; k < SM_INDEXPTRS_S(A0)[j + 1]; ++k)
        SM_ELEMENT_D(R0, SM_INDEXVALS_S(A0)[k], j) = SM_DATA_S(A0)[k];
      for (sunindextype k = SM_INDEXPTRS_S(B1)[j]; k < SM_INDEXPTRS_S(B1)[j + 1]; ++k)
        SM_ELEMENT_D(R1, SM_INDEXVALS_S(B1)[k], j) = SM_DATA_S(B1)[k];
    }
    for (sunindextype j = 0; j < kN; ++j)
      for (sunindextype i = 0; i < kN; ++i)
        EXPECT_DOUBLE_EQ(SM_ELEMENT_D(R0, i, j), SM_ELEMENT_D(R1, i, j)) << i << "," << j << " missing " << missing_diagonal;
    EXPECT_DOUBLE_EQ(SM_ELEMENT_D(R1, 4, 4), missing_diagonal ? 1.0 : 1.0 - 0.7 * SM_ELEMENT_D(D, 4, 4));
    for (SUNMatrix m : {A0, A1, B1, R0, R1}) SUNMatDestroy(m);
  }
  SUNMatDestroy(D);
}

INSTANTIATE_TEST_SUITE_P(Sizes, MatrixKernels, ::testing::Values(1, 2, 5, 12, 13, 16, 17, 30),
                         [](const ::testing::TestParamInfo<int>& i) { return "n" + std::to_string(i.param); });

}  // namespace
