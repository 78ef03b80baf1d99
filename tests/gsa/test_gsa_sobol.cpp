// Sobol' indices against analytic values (Ishigami, Sobol' G function), as SALib checks
// itself, and a test of the bootstrap intervals' coverage. The functions are the registered
// model kinds "ishigami" and "sobol_g": Ishigami runs through `phasmid gsa` and its HDF5 file,
// the G function through the sweep engine in-process, the repeated analyses through the
// kind's scenario.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>

#include "build_info.hpp"

#include "common/error.hpp"
#include "gsa/analysis.hpp"
#include "gsa/sampling.hpp"
#include "gsa_test_functions.hpp"

using namespace phasmid::gsa;
using gsa_test::GFunction;
using gsa_test::Ishigami;

namespace {

SobolIndices ishigami_indices(std::size_t n, std::uint64_t seed, std::size_t resamples) {
  SaltelliOptions so;
  so.n_base = n;
  so.second_order = true;
  so.seed = seed;
  const SaltelliDesign d = saltelli_sample(3, so);
  const std::vector<double> y = gsa_test::evaluate("ishigami", scale_to_parameters(d.unit, Ishigami::parameters()), 3);
  BootstrapOptions bo;
  bo.resamples = resamples;
  bo.seed = seed + 1000;
  return sobol_analyze(3, true, y, bo);
}

double tol(double ref) { return 0.05 + 0.1 * std::fabs(ref); }

}  // namespace

// configs/gsa_ishigami.toml (N = 8192, second order, seed 1) through the CLI verb; the indices
// are read back from the file it wrote.
TEST(GsaSobol, IshigamiIndicesAtN8192ThroughTheCli) {
  const Ishigami f;
  // The reference values are the rounded analytic ones.
  EXPECT_NEAR(f.v1() / f.variance(), 0.3139, 1e-4);
  EXPECT_NEAR(f.v2() / f.variance(), 0.4424, 1e-4);
  EXPECT_NEAR(f.v13() / f.variance(), 0.2437, 1e-4);
  const auto out = (std::filesystem::temp_directory_path() / "gsa_ishigami_cli.h5").string();
  std::filesystem::remove(out);
  const std::string cmd = std::string(PHASMID_BINARY) + " gsa configs/gsa_ishigami.toml -q -j 2 -o " + out;
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  phasmid::io::H5Reader file(out);
  EXPECT_EQ(file.read_doubles("/sweep/points").size(), 8192u * 8 * 3) << "N(2D+2) design points swept";
  const GsaResult r = read_gsa_h5(file);
  ASSERT_EQ(r.features.size(), 1u);
  const SobolIndices& s = r.features[0].sobol;
  const double s1[3] = {0.3139, 0.4424, 0.0}, st[3] = {0.5576, 0.4424, 0.2437};
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(s.S1[j], s1[j], tol(s1[j])) << "S1 of x" << j + 1;
    EXPECT_NEAR(s.ST[j], st[j], tol(st[j])) << "ST of x" << j + 1;
  }
  EXPECT_NEAR(s.S2[0 * 3 + 2], 0.2437, tol(0.2437)) << "S2(1,3)";
  EXPECT_NEAR(s.S2[0 * 3 + 1], 0.0, tol(0.0)) << "S2(1,2)";
  EXPECT_NEAR(s.S2[1 * 3 + 2], 0.0, tol(0.0)) << "S2(2,3)";
  EXPECT_TRUE(std::isnan(s.S2[2 * 3 + 0])) << "only the upper triangle is defined";
  EXPECT_NEAR(s.variance, f.variance(), 0.02 * f.variance());
  EXPECT_EQ(s.counts.n_used, 8192u);
  EXPECT_EQ(s.counts.n_dropped, 0u);
  // Convergence: nested subsets 8, 16, ..., 8192; the last is the full analysis.
  const FeatureResult& y = r.features[0];
  ASSERT_EQ(y.convergence_n.size(), 11u);
  EXPECT_EQ(y.convergence_n.front(), 8u);
  EXPECT_EQ(y.convergence_n.back(), 8192u);
  for (int j = 0; j < 3; ++j) EXPECT_EQ(y.sobol_convergence.back().ST[j], s.ST[j]);
  // Half-widths shrink roughly like 1/sqrt(n): 1024 -> 8192 narrows them by at least 2.
  EXPECT_GT(y.sobol_convergence[7].ST_conf[0], 2 * y.sobol_convergence[10].ST_conf[0]);
}

// configs/gsa_sobol_g.toml (N = 8192, first and total order) on the sweep engine.
TEST(GsaSobol, GFunctionFirstOrderWithin001OnTheSweepEngine) {
  const GFunction g{{78, 12, 0.5, 2, 97, 33}};
  const GsaResult r = gsa_test::run_gsa(phasmid::config::load_config("configs/gsa_sobol_g.toml"), "gsa_sobol_g.h5");
  ASSERT_EQ(r.features.size(), 1u);
  const SobolIndices& s = r.features[0].sobol;
  EXPECT_TRUE(s.S2.empty());
  for (std::size_t j = 0; j < 6; ++j) {
    EXPECT_NEAR(s.S1[j], g.s1(j), 0.01) << "S1 of x" << j + 1;
    EXPECT_LE(std::fabs(s.S1[j] - g.s1(j)), s.S1_conf[j]) << "the 95 % interval of x" << j + 1 << " covers the analytic value";
  }
}

// 50 independent replicates (scramble and bootstrap seeds differ): every 95 % interval must
// contain the analytic value in at least 45 of them.
TEST(GsaSobol, BootstrapIntervalsCoverIshigamiIn90PercentOf50Repetitions) {
  const Ishigami f;
  const double V = f.variance();
  const double s1[3] = {f.v1() / V, f.v2() / V, 0.0};
  const double st[3] = {(f.v1() + f.v13()) / V, f.v2() / V, f.v13() / V};
  const double s2_13 = f.v13() / V;
  int cover_s1[3] = {0, 0, 0}, cover_st[3] = {0, 0, 0}, cover_s2 = 0;
  for (std::uint64_t rep = 0; rep < 50; ++rep) {
    const SobolIndices s = ishigami_indices(512, 100 + rep, 200);
    for (int j = 0; j < 3; ++j) {
      cover_s1[j] += std::fabs(s.S1[j] - s1[j]) <= s.S1_conf[j];
      cover_st[j] += std::fabs(s.ST[j] - st[j]) <= s.ST_conf[j];
    }
    cover_s2 += std::fabs(s.S2[2] - s2_13) <= s.S2_conf[2];
  }
  for (int j = 0; j < 3; ++j) {
    EXPECT_GE(cover_s1[j], 45) << "S1 of x" << j + 1;
    EXPECT_GE(cover_st[j], 45) << "ST of x" << j + 1;
  }
  EXPECT_GE(cover_s2, 45) << "S2(1,3)";
}

// Non-finite outputs drop their whole base-row block: the result equals the analysis of the
// outputs with those blocks cut out, and the counts say how many.
TEST(GsaSobol, NonFiniteOutputsDropTheirBlock) {
  SaltelliOptions so;
  so.n_base = 256;
  so.second_order = true;
  so.seed = 3;
  const SaltelliDesign d = saltelli_sample(3, so);
  std::vector<double> y = gsa_test::evaluate("ishigami", scale_to_parameters(d.unit, Ishigami::parameters()), 3);
  const std::size_t blk = d.block();
  std::vector<double> kept;
  std::size_t n_failed_blocks = 0, n_bad = 0;
  for (std::size_t i = 0; i < so.n_base; ++i) {
    const bool fail = i % 10 == 4;  // one in ten blocks, a NaN or an infinity at varying rows
    if (fail) {
      ++n_failed_blocks, ++n_bad;
      y[i * blk + (i % blk)] = i % 20 == 4 ? std::numeric_limits<double>::quiet_NaN() : INFINITY;
      if (i % 30 == 4 && i % blk != 0) y[i * blk] = std::numeric_limits<double>::quiet_NaN(), ++n_bad;
    } else {
      kept.insert(kept.end(), y.begin() + i * blk, y.begin() + (i + 1) * blk);
    }
  }
  BootstrapOptions bo;
  bo.resamples = 0;
  const SobolIndices with_nan = sobol_analyze(3, true, y, bo);
  const SobolIndices clean = sobol_analyze(3, true, kept, bo);
  EXPECT_EQ(with_nan.counts.n_dropped, n_failed_blocks);
  EXPECT_EQ(with_nan.counts.n_used, so.n_base - n_failed_blocks);
  EXPECT_EQ(with_nan.counts.n_nonfinite, n_bad);
  EXPECT_GT(n_bad, n_failed_blocks);
  for (int j = 0; j < 3; ++j) {
    EXPECT_EQ(with_nan.S1[j], clean.S1[j]);
    EXPECT_EQ(with_nan.ST[j], clean.ST[j]);
  }
  EXPECT_EQ(with_nan.S2[2], clean.S2[2]);
}

// A rare 0/1 output: only base row 0's block varies, so about a third of the resamples (those
// without row 0) have no variance and no indices. The interval comes from the others.
TEST(GsaSobol, BootstrapSkipsResamplesWithoutVariance) {
  const std::size_t dim = 2, block = dim + 2, n = 20;
  std::vector<double> y(n * block, 0.0);
  y[0] = 1.0;          // f(A_0) = 1: x1 and x2 both matter through AB rows equal to 0
  y[block - 1] = 1.0;  // f(B_0) = 1
  y[1] = 1.0;          // f(AB(1)_0) = 1: changing x1 alone keeps the output
  BootstrapOptions bo;
  bo.resamples = 200;
  bo.seed = 5;
  const SobolIndices s = sobol_analyze(dim, false, y, bo);
  for (std::size_t j = 0; j < dim; ++j) {
    EXPECT_TRUE(std::isfinite(s.ST[j])) << j;
    EXPECT_TRUE(std::isfinite(s.ST_conf[j])) << "interval from the resamples that contain row 0, x" << j + 1;
  }
  EXPECT_GT(s.ST_conf[1], 0.0);
  EXPECT_EQ(s.ST_conf[0], 0.0) << "x1's ST is 0 in every resample";
  // Analytic on these outputs: V = var of {1, 0 x 19, 1, 0 x 19} (divisor 40) = 2/40 - (2/40)^2;
  // ST_2 = mean((f_A - f_AB(2))^2) / (2V) = (1/20) / (2V).
  const double V = 2.0 / 40 - (2.0 / 40) * (2.0 / 40);
  EXPECT_NEAR(s.ST[1], (1.0 / 20) / (2 * V), 1e-12);
  EXPECT_NEAR(s.ST[0], 0.0, 1e-12);
}

TEST(GsaSobol, RejectsOutputsThatAreNotWholeBlocks) {
  EXPECT_THROW(sobol_analyze(3, true, std::vector<double>(17, 1.0), BootstrapOptions{}), phasmid::Error);
  BootstrapOptions bad;
  bad.confidence = 1.0;
  EXPECT_THROW(sobol_analyze(3, false, std::vector<double>(10, 1.0), bad), phasmid::Error);
}

TEST(GsaSobol, NormalQuantile) {
  EXPECT_NEAR(normal_quantile(0.975), 1.959963984540054, 1e-12);
  EXPECT_NEAR(normal_quantile(0.5), 0.0, 1e-14);
  EXPECT_NEAR(normal_quantile(0.05), -1.6448536269514729, 1e-12);
}
