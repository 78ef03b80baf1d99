// phasmid's compiled serial-vector kernels (solver/serial_kernels.hpp) against SUNDIALS' own
// serial implementations, operation by operation, including the aliasing CVODES uses
// (result == operand).
#include <gtest/gtest.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "solver/serial_kernels.hpp"

namespace {

using phasmid::solver::install_serial_kernels;

// Lengths of the short-vector kernels (up to 32: each remainder of four, both ends) and above
// them (33, 37: the loops, with their remainders).
class SerialKernels : public ::testing::TestWithParam<int> {
 protected:
  const sunindextype kN = GetParam();
  void SetUp() override {
    ASSERT_EQ(SUNContext_Create(nullptr, &ctx_), 0);
    ref_ = N_VNew_Serial(kN, ctx_);
    ours_ = N_VNew_Serial(kN, ctx_);
    install_serial_kernels(ours_);
  }
  void TearDown() override {
    for (N_Vector v : owned_) N_VDestroy(v);
    N_VDestroy(ref_);
    N_VDestroy(ours_);
    SUNContext_Free(&ctx_);
  }
  // A pair of vectors with equal random contents: one with SUNDIALS' ops, one with ours.
  std::pair<N_Vector, N_Vector> pair(bool with_zero = false) {
    N_Vector a = N_VClone(ref_), b = N_VClone(ours_);
    owned_.push_back(a);
    owned_.push_back(b);
    for (sunindextype i = 0; i < kN; ++i) {
      double v = dist_(rng_);
      if (with_zero && i == kN / 2) v = 0.0;
      NV_Ith_S(a, i) = NV_Ith_S(b, i) = v;
    }
    return {a, b};
  }
  void expect_equal(N_Vector a, N_Vector b) const {
    for (sunindextype i = 0; i < kN; ++i) EXPECT_NEAR(NV_Ith_S(a, i), NV_Ith_S(b, i), 1e-14 * (1 + std::abs(NV_Ith_S(a, i)))) << i;
  }
  SUNContext ctx_ = nullptr;
  N_Vector ref_ = nullptr, ours_ = nullptr;
  std::vector<N_Vector> owned_;
  std::mt19937 rng_{42};
  std::uniform_real_distribution<double> dist_{-2.0, 3.0};
};

TEST_P(SerialKernels, ClonesInheritTheKernelsAndTheOriginalIsUntouched) {
  N_Vector c = N_VClone(ours_);
  owned_.push_back(c);
  EXPECT_EQ(c->ops->nvlinearsum, ours_->ops->nvlinearsum);
  EXPECT_NE(ours_->ops->nvlinearsum, ref_->ops->nvlinearsum);
  EXPECT_EQ(N_VGetLength(c), kN);
}

TEST_P(SerialKernels, ElementwiseOperationsMatchSundials) {
  auto [x0, x1] = pair();
  auto [y0, y1] = pair();
  auto [z0, z1] = pair();
  N_VLinearSum(0.7, x0, -1.3, y0, z0);
  N_VLinearSum(0.7, x1, -1.3, y1, z1);
  expect_equal(z0, z1);
  N_VLinearSum(0.7, x0, 2.0, z0, z0);  // z = a x + b z (aliasing)
  N_VLinearSum(0.7, x1, 2.0, z1, z1);
  expect_equal(z0, z1);
  N_VConst(4.5, z0);
  N_VConst(4.5, z1);
  expect_equal(z0, z1);
  N_VProd(x0, y0, z0);
  N_VProd(x1, y1, z1);
  expect_equal(z0, z1);
  N_VDiv(x0, y0, z0);
  N_VDiv(x1, y1, z1);
  expect_equal(z0, z1);
  N_VScale(-3.0, x0, z0);
  N_VScale(-3.0, x1, z1);
  expect_equal(z0, z1);
  N_VAbs(z0, z0);
  N_VAbs(z1, z1);
  expect_equal(z0, z1);
  N_VInv(z0, z0);
  N_VInv(z1, z1);
  expect_equal(z0, z1);
  N_VAddConst(x0, 0.25, z0);
  N_VAddConst(x1, 0.25, z1);
  expect_equal(z0, z1);
  N_VCompare(1.0, x0, z0);
  N_VCompare(1.0, x1, z1);
  expect_equal(z0, z1);
  auto [w0, w1] = pair(true);
  EXPECT_EQ(N_VInvTest(w0, z0), N_VInvTest(w1, z1));
  EXPECT_EQ(N_VInvTest(w1, z1), SUNFALSE);
  expect_equal(z0, z1);
}

TEST_P(SerialKernels, ReductionsMatchSundials) {
  auto [x0, x1] = pair();
  auto [y0, y1] = pair();
  auto [id0, id1] = pair();
  EXPECT_NEAR(N_VDotProd(x0, y0), N_VDotProd(x1, y1), 1e-12);
  EXPECT_DOUBLE_EQ(N_VMaxNorm(x0), N_VMaxNorm(x1));
  EXPECT_NEAR(N_VWrmsNorm(x0, y0), N_VWrmsNorm(x1, y1), 1e-13);
  EXPECT_NEAR(N_VWrmsNormMask(x0, y0, id0), N_VWrmsNormMask(x1, y1, id1), 1e-13);
  EXPECT_DOUBLE_EQ(N_VMin(x0), N_VMin(x1));
  EXPECT_NEAR(N_VWL2Norm(x0, y0), N_VWL2Norm(x1, y1), 1e-12);
  EXPECT_NEAR(N_VL1Norm(x0), N_VL1Norm(x1), 1e-12);
  EXPECT_NEAR(N_VWSqrSumLocal(x0, y0), N_VWSqrSumLocal(x1, y1), 1e-11);
  EXPECT_NEAR(N_VWSqrSumMaskLocal(x0, y0, id0), N_VWSqrSumMaskLocal(x1, y1, id1), 1e-11);
}

TEST_P(SerialKernels, FusedAndArrayOperationsMatchSundials) {
  constexpr int m = 3, k = 4;
  std::vector<N_Vector> X0, X1, Y0, Y1, Z0, Z1;
  for (int i = 0; i < k; ++i) {
    auto [a, b] = pair();
    X0.push_back(a), X1.push_back(b);
    auto [c, d] = pair();
    Y0.push_back(c), Y1.push_back(d);
    auto [e, f] = pair();
    Z0.push_back(e), Z1.push_back(f);
  }
  std::vector<double> c{0.5, -1.5, 2.0, 0.25};
  double r0[k], r1[k];
  // z = sum c_i X_i, once into a separate vector and once into X_0 itself.
  ASSERT_EQ(N_VLinearCombination(k, c.data(), X0.data(), Z0[0]), 0);
  ASSERT_EQ(N_VLinearCombination(k, c.data(), X1.data(), Z1[0]), 0);
  expect_equal(Z0[0], Z1[0]);
  ASSERT_EQ(N_VLinearCombination(k, c.data(), Y0.data(), Y0[0]), 0);
  ASSERT_EQ(N_VLinearCombination(k, c.data(), Y1.data(), Y1[0]), 0);
  expect_equal(Y0[0], Y1[0]);
  ASSERT_EQ(N_VScaleAddMulti(k, c.data(), X0[1], Y0.data(), Z0.data()), 0);
  ASSERT_EQ(N_VScaleAddMulti(k, c.data(), X1[1], Y1.data(), Z1.data()), 0);
  for (int i = 0; i < k; ++i) expect_equal(Z0[i], Z1[i]);
  ASSERT_EQ(N_VDotProdMulti(k, X0[2], Y0.data(), r0), 0);
  ASSERT_EQ(N_VDotProdMulti(k, X1[2], Y1.data(), r1), 0);
  for (int i = 0; i < k; ++i) EXPECT_NEAR(r0[i], r1[i], 1e-12);
  ASSERT_EQ(N_VLinearSumVectorArray(k, 1.5, X0.data(), -0.5, Y0.data(), Z0.data()), 0);
  ASSERT_EQ(N_VLinearSumVectorArray(k, 1.5, X1.data(), -0.5, Y1.data(), Z1.data()), 0);
  for (int i = 0; i < k; ++i) expect_equal(Z0[i], Z1[i]);
  ASSERT_EQ(N_VScaleVectorArray(k, c.data(), X0.data(), Z0.data()), 0);
  ASSERT_EQ(N_VScaleVectorArray(k, c.data(), X1.data(), Z1.data()), 0);
  for (int i = 0; i < k; ++i) expect_equal(Z0[i], Z1[i]);
  ASSERT_EQ(N_VWrmsNormVectorArray(k, X0.data(), Y0.data(), r0), 0);
  ASSERT_EQ(N_VWrmsNormVectorArray(k, X1.data(), Y1.data(), r1), 0);
  for (int i = 0; i < k; ++i) EXPECT_NEAR(r0[i], r1[i], 1e-13);
  ASSERT_EQ(N_VWrmsNormMaskVectorArray(k, X0.data(), Y0.data(), Z0[3], r0), 0);
  ASSERT_EQ(N_VWrmsNormMaskVectorArray(k, X1.data(), Y1.data(), Z1[3], r1), 0);
  for (int i = 0; i < k; ++i) EXPECT_NEAR(r0[i], r1[i], 1e-13);
  ASSERT_EQ(N_VConstVectorArray(k, -7.0, Z0.data()), 0);
  ASSERT_EQ(N_VConstVectorArray(k, -7.0, Z1.data()), 0);
  for (int i = 0; i < k; ++i) expect_equal(Z0[i], Z1[i]);

  // Arrays of arrays (the sensitivity vectors): Y[j][i], j < m sums of k vectors.
  std::vector<std::vector<N_Vector>> YY0(m), YY1(m), ZZ0(m), ZZ1(m);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < k; ++i) {
      auto [a, b] = pair();
      YY0[j].push_back(a), YY1[j].push_back(b);
      auto [e, f] = pair();
      ZZ0[j].push_back(e), ZZ1[j].push_back(f);
    }
  std::vector<N_Vector*> pY0, pY1, pZ0, pZ1;
  for (int j = 0; j < m; ++j) {
    pY0.push_back(YY0[j].data()), pY1.push_back(YY1[j].data());
    pZ0.push_back(ZZ0[j].data()), pZ1.push_back(ZZ1[j].data());
  }
  ASSERT_EQ(N_VScaleAddMultiVectorArray(k, m, c.data(), X0.data(), pY0.data(), pZ0.data()), 0);
  ASSERT_EQ(N_VScaleAddMultiVectorArray(k, m, c.data(), X1.data(), pY1.data(), pZ1.data()), 0);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < k; ++i) expect_equal(ZZ0[j][i], ZZ1[j][i]);
  // Z[i] = sum_j c_j Y[j][i], into separate vectors and into Y[0][i] itself.
  ASSERT_EQ(N_VLinearCombinationVectorArray(k, m, c.data(), pY0.data(), Z0.data()), 0);
  ASSERT_EQ(N_VLinearCombinationVectorArray(k, m, c.data(), pY1.data(), Z1.data()), 0);
  for (int i = 0; i < k; ++i) expect_equal(Z0[i], Z1[i]);
  ASSERT_EQ(N_VLinearCombinationVectorArray(k, m, c.data(), pY0.data(), YY0[0].data()), 0);
  ASSERT_EQ(N_VLinearCombinationVectorArray(k, m, c.data(), pY1.data(), YY1[0].data()), 0);
  for (int i = 0; i < k; ++i) expect_equal(YY0[0][i], YY1[0][i]);
}

}  // namespace

// Linear combinations of 1 vector, of the one-pass kernel's largest count (16) and of more (20,
// the pass-per-vector loop), into a separate vector and into X_0 itself.
TEST_P(SerialKernels, LinearCombinationOfAnyCountMatchesSundials) {
  for (int k : {1, 2, 16, 20}) {
    std::vector<N_Vector> X0, X1;
    std::vector<double> c;
    for (int i = 0; i < k; ++i) {
      auto [a, b] = pair();
      X0.push_back(a), X1.push_back(b);
      c.push_back(dist_(rng_));
    }
    auto [z0, z1] = pair();
    ASSERT_EQ(N_VLinearCombination(k, c.data(), X0.data(), z0), 0);
    ASSERT_EQ(N_VLinearCombination(k, c.data(), X1.data(), z1), 0);
    expect_equal(z0, z1);
    ASSERT_EQ(N_VLinearCombination(k, c.data(), X0.data(), X0[0]), 0);
    ASSERT_EQ(N_VLinearCombination(k, c.data(), X1.data(), X1[0]), 0);
    expect_equal(X0[0], X1[0]);
  }
}

INSTANTIATE_TEST_SUITE_P(Lengths, SerialKernels, ::testing::Values(1, 2, 3, 4, 5, 6, 7, 8, 9, 12, 14, 15, 16, 17, 26, 31, 32, 33, 37),
                         [](const ::testing::TestParamInfo<int>& i) { return "n" + std::to_string(i.param); });
