// Saltelli designs: block structure, scrambled Sobol' base points, parameter scaling.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "common/error.hpp"
#include "gsa/sampling.hpp"
#include "sweep/design.hpp"

using namespace phasmid::gsa;

TEST(GsaSampling, SaltelliBlocksInSALibOrder) {
  const std::size_t D = 4, N = 64;
  for (bool second : {false, true}) {
    SaltelliOptions o;
    o.n_base = N;
    o.second_order = second;
    const SaltelliDesign s = saltelli_sample(D, o);
    ASSERT_EQ(s.rows(), N * (second ? 2 * D + 2 : D + 2));
    ASSERT_EQ(s.unit.size(), s.rows() * D);
    const std::vector<double> base = scrambled_sobol_points(N, 2 * D, true, 0, o.seed);
    for (std::size_t i = 0; i < N; ++i) {
      auto at = [&](std::size_t row, std::size_t d) { return s.unit[(i * s.block() + row) * D + d]; };
      for (std::size_t d = 0; d < D; ++d) {
        const double a = base[i * 2 * D + d], b = base[i * 2 * D + D + d];
        ASSERT_EQ(at(0, d), a);
        ASSERT_EQ(at(s.block() - 1, d), b);
        for (std::size_t j = 0; j < D; ++j) {
          ASSERT_EQ(at(1 + j, d), d == j ? b : a) << "AB^(" << j << ")";
          if (second) {
            ASSERT_EQ(at(1 + D + j, d), d == j ? a : b) << "BA^(" << j << ")";
          }
        }
      }
    }
  }
}

// Scrambling keeps the net: 2^m scrambled points put exactly one point in every interval
// [k/2^m, (k+1)/2^m) of each coordinate, and every pair of coordinates one point per cell of
// a 2^(m/2) x 2^(m/2) grid (the first two Sobol' dimensions form a (0,m,2)-net).
TEST(GsaSampling, ScrambledSobolKeepsStratification) {
  const std::size_t n = 256, dim = 6;
  for (std::uint64_t seed : {1u, 2u}) {
    const auto u = scrambled_sobol_points(n, dim, true, 0, seed);
    for (std::size_t d = 0; d < dim; ++d) {
      std::set<long> cells;
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_GE(u[i * dim + d], 0.0);
        ASSERT_LT(u[i * dim + d], 1.0);
        cells.insert(static_cast<long>(std::floor(u[i * dim + d] * n)));
      }
      EXPECT_EQ(cells.size(), n) << "dimension " << d;
    }
    std::set<long> cells2;
    for (std::size_t i = 0; i < n; ++i)
      cells2.insert(static_cast<long>(std::floor(u[i * dim] * 16)) * 16 + static_cast<long>(std::floor(u[i * dim + 1] * 16)));
    EXPECT_EQ(cells2.size(), n);
  }
  EXPECT_NE(scrambled_sobol_points(8, 2, true, 0, 1), scrambled_sobol_points(8, 2, true, 0, 2));
}

TEST(GsaSampling, UnscrambledSkipDropsLeadingPoints) {
  const auto all = phasmid::sweep::sobol_points(20, 3);
  const auto skipped = scrambled_sobol_points(12, 3, false, 8, 0);
  EXPECT_EQ(skipped, std::vector<double>(all.begin() + 8 * 3, all.end()));
}

TEST(GsaSampling, ScaleToParametersLinearAndLog) {
  std::vector<Parameter> ps(2);
  ps[0].lower = -2, ps[0].upper = 6;
  ps[1].lower = 1, ps[1].upper = 100, ps[1].log_scale = true;
  const auto x = scale_to_parameters({0.0, 0.0, 0.25, 0.5, 1.0, 1.0}, ps);
  EXPECT_DOUBLE_EQ(x[0], -2.0);
  EXPECT_DOUBLE_EQ(x[1], 1.0);
  EXPECT_DOUBLE_EQ(x[2], 0.0);
  EXPECT_NEAR(x[3], 10.0, 1e-12);
  EXPECT_DOUBLE_EQ(x[4], 6.0);
  EXPECT_DOUBLE_EQ(x[5], 100.0);
  EXPECT_THROW(scale_to_parameters({0.5, 0.5, 0.5}, ps), phasmid::Error);
}

TEST(GsaSampling, RejectsTooManyParametersForTheSequence) {
  SaltelliOptions o;
  EXPECT_THROW(saltelli_sample(17, o), phasmid::Error);  // needs a 34-dimensional sequence
}

// The first n blocks of a design are the design of base size n (convergence from nested
// subsets of one run).
TEST(GsaSampling, SaltelliDesignsAreNested) {
  SaltelliOptions big, small;
  big.n_base = 128, small.n_base = 32;
  big.seed = small.seed = 17;
  big.skip = small.skip = 4;
  const SaltelliDesign b = saltelli_sample(3, big), s = saltelli_sample(3, small);
  EXPECT_EQ(std::vector<double>(b.unit.begin(), b.unit.begin() + s.unit.size()), s.unit);
}
