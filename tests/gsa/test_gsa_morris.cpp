// Morris screening: designs on the p-level grid, elementary effects on Ishigami.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "common/error.hpp"
#include "gsa/analysis.hpp"
#include "gsa/gsa_h5.hpp"
#include "gsa/sampling.hpp"
#include "gsa_test_functions.hpp"

using namespace phasmid::gsa;
using gsa_test::Ishigami;

namespace {

// Morris on the registered kind "ishigami", run by `phasmid gsa`'s path on the sweep engine.
phasmid::config::Config morris_config(std::size_t pool) {
  std::string text = "[model]\ntype = \"ishigami\"\n";
  for (const char* x : {"x1", "x2", "x3"})
    text += std::string("[[sweep.parameter]]\nname = \"") + x + "\"\nlower = -3.141592653589793\nupper = 3.141592653589793\n";
  text += "[gsa]\nmethod = \"morris\"\ntrajectories = 20\nlevels = 4\nseed = 11\nbootstrap = 500\nfeatures = [\"y\"]\npool = " +
          std::to_string(pool) + "\n";
  return phasmid::config::parse_config(text, "morris_test.toml");
}

}  // namespace

// With p = 4 levels, Delta = 4/6 = 2/3 and a step of x2 goes between u = 0 and 2/3 or between
// 1/3 and 1, i.e. x2 = -pi <-> pi/3 or -pi/3 <-> pi. x2 enters Ishigami only through
// a sin^2 x2, and sin^2(pi/3) - sin^2(pi) = 3/4 = sin^2(-pi/3) - sin^2(-pi) in magnitude, so every
// elementary effect of x2 is +-(7 * 3/4) / (2/3) = +-7.875 whatever the other coordinates:
// mu*(x2) = 7.875 for any trajectories.
TEST(GsaMorris, IshigamiMuStarOfX2Is7875WithFourLevels) {
  for (std::size_t pool : {std::size_t(0), std::size_t(40)}) {
    const GsaResult r = gsa_test::run_gsa(morris_config(pool), "gsa_morris.h5");
    EXPECT_DOUBLE_EQ(r.morris.delta, 2.0 / 3.0);
    EXPECT_EQ(r.morris.rows(), 20u * 4);
    ASSERT_EQ(r.features.size(), 1u);
    const MorrisIndices& m = r.features[0].morris;
    EXPECT_NEAR(m.mu_star[1], 7.875, 1e-12) << "pool " << pool;
    EXPECT_NEAR(m.mu_star_conf[1], 0.0, 1e-12) << "all effects of x2 have the same magnitude";
    EXPECT_LE(std::fabs(m.mu[1]), 7.875 + 1e-12);
    EXPECT_EQ(m.counts.n_used, 20u);
    // x1 and x3 interact (b x3^4 sin x1): their effects vary, so sigma > 0 and the interval is open.
    EXPECT_GT(m.sigma[0], 0.1);
    EXPECT_GT(m.mu_star_conf[2], 0.0);
    EXPECT_GE(m.mu_star[0], std::fabs(m.mu[0]) * (1 - 1e-14));
  }
}

TEST(GsaMorris, TrajectoriesMoveEachCoordinateOnceByDeltaOnTheGrid) {
  MorrisOptions mo;
  mo.trajectories = 15;
  mo.levels = 6;
  mo.seed = 5;
  const std::size_t D = 4;
  const MorrisDesign d = morris_sample(D, mo);
  ASSERT_EQ(d.unit.size(), 15u * (D + 1) * D);
  EXPECT_DOUBLE_EQ(d.delta, 6.0 / 10.0);
  for (double u : d.unit) {
    const double level = u * (mo.levels - 1);
    EXPECT_NEAR(level, std::round(level), 1e-12);
    EXPECT_GE(u, 0.0);
    EXPECT_LE(u, 1.0);
  }
  for (std::size_t t = 0; t < d.trajectories; ++t) {
    std::set<std::size_t> moved;
    for (std::size_t k = 0; k < D; ++k) {
      const double* x0 = &d.unit[(t * (D + 1) + k) * D];
      for (std::size_t j = 0; j < D; ++j)
        if (x0[D + j] != x0[j]) {
          EXPECT_NEAR(std::fabs(x0[D + j] - x0[j]), d.delta, 1e-12);
          moved.insert(j);
        }
    }
    EXPECT_EQ(moved.size(), D) << "trajectory " << t;
  }
}

// Campolongo's criterion: the selected trajectories are spread more widely than the same
// number drawn without selection.
TEST(GsaMorris, SelectionFromAPoolIncreasesSpread) {
  const std::size_t D = 5, r = 8;
  auto spread = [&](const MorrisDesign& d) {
    double sum = 0;
    for (std::size_t a = 0; a < r; ++a)
      for (std::size_t b = a + 1; b < r; ++b) {
        double dab = 0;
        for (std::size_t i = 0; i <= D; ++i)
          for (std::size_t j = 0; j <= D; ++j) {
            double s2 = 0;
            for (std::size_t k = 0; k < D; ++k) s2 += std::pow(d.unit[(a * (D + 1) + i) * D + k] - d.unit[(b * (D + 1) + j) * D + k], 2);
            dab += std::sqrt(s2);
          }
        sum += dab * dab;
      }
    return std::sqrt(sum);
  };
  MorrisOptions plain;
  plain.trajectories = r;
  plain.seed = 9;
  MorrisOptions selected = plain;
  selected.pool = 60;
  EXPECT_GT(spread(morris_sample(D, selected)), 1.05 * spread(morris_sample(D, plain)));
}

TEST(GsaMorris, TrajectoryWithNonFiniteOutputIsDropped) {
  MorrisOptions mo;
  mo.trajectories = 10;
  mo.seed = 2;
  const MorrisDesign d = morris_sample(3, mo);
  auto y = gsa_test::evaluate("ishigami", scale_to_parameters(d.unit, Ishigami::parameters()), 3);
  y[2 * 4 + 1] = std::numeric_limits<double>::quiet_NaN();  // trajectory 2
  y[7 * 4 + 3] = std::numeric_limits<double>::quiet_NaN();  // trajectory 7
  BootstrapOptions bo;
  bo.resamples = 0;
  const MorrisIndices m = morris_analyze(d, y, bo);
  EXPECT_EQ(m.counts.n_dropped, 2u);
  EXPECT_EQ(m.counts.n_used, 8u);
  EXPECT_EQ(m.counts.n_nonfinite, 2u);
  EXPECT_NEAR(m.mu_star[1], 7.875, 1e-12);
}

TEST(GsaMorris, RejectsOddLevelsAndSmallPools) {
  MorrisOptions mo;
  mo.levels = 5;
  EXPECT_THROW(morris_sample(3, mo), phasmid::Error);
  mo.levels = 4;
  mo.pool = mo.trajectories;
  EXPECT_THROW(morris_sample(3, mo), phasmid::Error);
}
