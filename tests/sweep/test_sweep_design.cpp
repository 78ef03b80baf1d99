// Sweep designs and the [sweep] parser: known Sobol' points, Latin-hypercube strata, grid order,
// and bad input naming file:line.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "common/error.hpp"
#include "config/config.hpp"
#include "sweep/design.hpp"
#include "config/sweep_section.hpp"

using namespace phasmid;

TEST(SweepDesign, SobolMatchesPublishedFirstPoints) {
  // scipy.stats.qmc.Sobol(d=3, scramble=False).random(8) (Joe-Kuo direction numbers)
  const double want[8][3] = {{0, 0, 0},           {0.5, 0.5, 0.5},     {0.75, 0.25, 0.25},
                             {0.25, 0.75, 0.75},  {0.375, 0.375, 0.625}, {0.875, 0.875, 0.125},
                             {0.625, 0.125, 0.875}, {0.125, 0.625, 0.375}};
  auto x = sweep::sobol_points(8, 3);
  for (int i = 0; i < 8; ++i)
    for (int d = 0; d < 3; ++d) EXPECT_EQ(x[i * 3 + d], want[i][d]) << "point " << i << " dim " << d;
}

TEST(SweepDesign, SobolFirstPowerOfTwoPointsAreStratifiedInEveryDimension) {
  const size_t n = 64, dim = 32;
  auto x = sweep::sobol_points(n, dim);
  for (size_t d = 0; d < dim; ++d) {
    std::set<int> strata;
    for (size_t i = 0; i < n; ++i) strata.insert(static_cast<int>(x[i * dim + d] * n));
    EXPECT_EQ(strata.size(), n) << "dimension " << d;
  }
  EXPECT_THROW(sweep::sobol_points(4, 33), Error);
}

TEST(SweepDesign, LatinHypercubeHasOnePointPerStratumAndDependsOnlyOnSeed) {
  const size_t n = 50, dim = 4;
  auto a = sweep::lhs_points(n, dim, 7), b = sweep::lhs_points(n, dim, 7), c = sweep::lhs_points(n, dim, 8);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  for (size_t d = 0; d < dim; ++d) {
    std::set<int> strata;
    for (size_t i = 0; i < n; ++i) {
      EXPECT_GE(a[i * dim + d], 0.0);
      EXPECT_LT(a[i * dim + d], 1.0);
      strata.insert(static_cast<int>(a[i * dim + d] * n));
    }
    EXPECT_EQ(strata.size(), n);
  }
}

namespace {
const char* kModel = R"([model]
type = "mechanical_joint"
leg = "middle"
joint = "fti"
[simulation]
t_end_ms = 2000
discard_ms = 500
)";

sweep::SweepSpec parse(const std::string& sweep_text) {
  config::Config cfg = config::parse_config(std::string(kModel) + sweep_text, "s.toml");
  auto m = config::build_model(cfg);
  return sweep::parse_sweep(cfg, m->parameters(), config::simulation_settings(cfg));
}

std::string error_of(const std::string& sweep_text) {
  try {
    parse(sweep_text);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST(SweepConfig, GridIsFullFactorialWithLastParameterFastest) {
  auto s = parse(R"([sweep]
t_end_ms = 1500
[[sweep.parameter]]
name = "middle.fti.b_v"
values = [5, 10]
[[sweep.parameter]]
name = "middle.fti.k_E.flexion"
lower = 300
upper = 700
points = 3
)");
  ASSERT_EQ(s.n_points, 6u);
  EXPECT_EQ(s.names(), (std::vector<std::string>{"middle.fti.b_v", "middle.fti.k_E.flexion"}));
  const double want[6][2] = {{5, 300}, {5, 500}, {5, 700}, {10, 300}, {10, 500}, {10, 700}};
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(s.at(i, 0), want[i][0]);
    EXPECT_EQ(s.at(i, 1), want[i][1]);
  }
  EXPECT_EQ(s.t_end_ms, 1500);   // overridden in [sweep]
  EXPECT_EQ(s.discard_ms, 500);  // from [simulation]
}

TEST(SweepConfig, LhsAndSobolMapIntoBoundsIncludingLogScale) {
  for (std::string design : {"lhs", "sobol"}) {
    auto s = parse("[sweep]\ndesign = \"" + design + R"("
points = 16
seed = 3
[[sweep.parameter]]
name = "middle.fti.b_v"
lower = 1
upper = 100
scale = "log"
[[sweep.parameter]]
name = "middle.fti.k_E.flexion"
lower = 300
upper = 700
)");
    ASSERT_EQ(s.n_points, 16u);
    size_t below_10 = 0;
    for (size_t i = 0; i < 16; ++i) {
      EXPECT_GE(s.at(i, 0), 1.0);
      EXPECT_LE(s.at(i, 0), 100.0);
      EXPECT_GE(s.at(i, 1), 300.0);
      EXPECT_LE(s.at(i, 1), 700.0);
      below_10 += s.at(i, 0) < 10.0;
    }
    EXPECT_EQ(below_10, 8u) << design << ": log scale puts half the points in [1, 10)";
  }
}

TEST(SweepConfig, BadInputNamesFileAndLine) {
  EXPECT_NE(error_of("[sweep]\n[[sweep.parameter]]\nname = \"middle.fti.bv\"\nvalues = [1]\n")
                .find("s.toml:10: unknown parameter 'middle.fti.bv'"),
            std::string::npos);
  EXPECT_NE(error_of("[sweep]\n[[sweep.parameter]]\nname = \"middle.fti.b_v\"\nvalues = [1, -2]\n")
                .find("s.toml:11: impossible value -2"),
            std::string::npos);
  EXPECT_NE(error_of("[sweep]\ndesing = \"lhs\"\n").find("s.toml:9: unknown key 'desing'"), std::string::npos);
  EXPECT_NE(error_of("[sweep]\ndesign = \"halton\"\n").find("s.toml:9: design must be"), std::string::npos);
  EXPECT_NE(error_of("[sweep]\ndesign = \"lhs\"\n[[sweep.parameter]]\nname = \"middle.fti.b_v\"\nvalues = [1]\n")
                .find("s.toml:12: 'values' is for design = \"grid\""),
            std::string::npos);
  EXPECT_NE(error_of("[sweep]\ndesign = \"sobol\"\n[[sweep.parameter]]\nname = \"middle.fti.b_v\"\nlower = 1\nupper = 2\n")
                .find("needs points = N"),
            std::string::npos);
  EXPECT_NE(error_of("[sweep]\n[[sweep.parameter]]\nname = \"middle.fti.b_v\"\nlower = 5\nupper = 2\npoints = 3\n")
                .find("s.toml:12: 'upper' must be greater than 'lower'"),
            std::string::npos);
  EXPECT_NE(error_of("[sweep]\ndiscard_ms = 3000\n[[sweep.parameter]]\nname = \"middle.fti.b_v\"\nvalues = [1]\n")
                .find("s.toml:9: discard_ms"),
            std::string::npos);
  EXPECT_NE(error_of("[sweep]\npoints = 0\n").find("s.toml:9: 'points' must be a positive integer"), std::string::npos);
  EXPECT_NE(error_of("").find("missing [sweep]"), std::string::npos);
  EXPECT_NE(error_of("[sweep]\n[[sweep.parameter]]\nname = \"middle.fti.b_v\"\nvalues = [1]\n[[sweep.parameter]]\n"
                     "name = \"middle.fti.b_v\"\nvalues = [2]\n")
                .find("s.toml:13: parameter 'middle.fti.b_v' swept twice"),
            std::string::npos);
}

TEST(SweepConfig, LinkedNamesFormOneAxisAndOptionsMultiplyTheDesign) {
  auto s = parse(R"([sweep]
[[sweep.option]]
name = "start_phase"
values = ["flexion", "extension"]
[[sweep.parameter]]
names = ["middle.fti.k_E.flexion", "middle.fti.k_F.flexion"]
values = [[510.0, 296.0], [600.0, 350.0], [700.0, 400.0]]
[[sweep.parameter]]
name = "middle.fti.b_v"
values = [10.0, 12.5]
)");
  ASSERT_EQ(s.n_design, 6u);
  ASSERT_EQ(s.n_combos, 2u);
  ASSERT_EQ(s.n_points, 12u);
  ASSERT_EQ(s.parameters.size(), 3u);
  // rows move together; b_v fastest; the option slowest
  const double want[6][3] = {{510, 296, 10}, {510, 296, 12.5}, {600, 350, 10},
                             {600, 350, 12.5}, {700, 400, 10}, {700, 400, 12.5}};
  for (size_t i = 0; i < 12; ++i)
    for (size_t d = 0; d < 3; ++d) EXPECT_EQ(s.at(i, d), want[i % 6][d]) << i << "," << d;
  EXPECT_EQ(s.combo_of(5), 0u);
  EXPECT_EQ(s.combo_of(6), 1u);
  EXPECT_EQ(s.describe_combo(1), "start_phase = extension");
  config::Config cfg = config::parse_config(std::string(kModel) + "[sweep]\n[[sweep.option]]\nname = \"start_phase\"\n"
                                            "values = [\"flexion\", \"extension\"]\n[[sweep.parameter]]\n"
                                            "name = \"middle.fti.b_v\"\nvalues = [1]\n", "s.toml");
  auto m = config::build_model(cfg);
  auto spec = sweep::parse_sweep(cfg, m->parameters(), config::simulation_settings(cfg));
  EXPECT_EQ(*sweep::config_for(cfg, spec, 1).table["model"]["start_phase"].value<std::string>(), "extension");
  EXPECT_EQ(*sweep::config_for(cfg, spec, 0).table["model"]["start_phase"].value<std::string>(), "flexion");

  EXPECT_NE(error_of("[sweep]\n[[sweep.parameter]]\nnames = [\"middle.fti.b_v\", \"middle.fti.d\"]\nvalues = [[1, 0.3], [2]]\n")
                .find("s.toml:11: each row of 'values' needs 2 numbers"),
            std::string::npos);
  EXPECT_NE(error_of("[sweep]\n[[sweep.option]]\nname = \"type\"\nvalues = [\"single_joint\"]\n[[sweep.parameter]]\n"
                     "name = \"middle.fti.b_v\"\nvalues = [1]\n")
                .find("s.toml:10: the model type cannot be swept"),
            std::string::npos);
}

#include "sweep/sweep_runner.hpp"
TEST(SweepGaitClass, LabelFromTheGaitClassFeatureElseOk) {
  EXPECT_EQ(sweep::gait_class_of({{"period_ms", 500, "ms"}}), "ok");
  EXPECT_EQ(sweep::gait_class_of({{"period_ms", 500, "ms"}, {"gait_class", 2, "1"}}), "tripod");
  EXPECT_EQ(sweep::gait_class_of({{"gait_class", 1, "1"}}), "tetrapod");
  EXPECT_EQ(sweep::gait_class_of({{"gait_class", 0, "1"}}), "irregular");
}

#include <cmath>
#include <cstring>

#include "sweep/sweep_store.hpp"
TEST(SweepJournal, RecordsRoundTripBitExactlyAndRejectCorruption) {
  sweep::PointResult r;
  r.status = "CVODES failed at t = 0 ms:\nline two \xc3\xa9";  // newline and UTF-8 must stay on one line
  r.gait_class = "failed";
  r.features = {{"period_ms", 0.1 + 0.2, "ms"}, {"x", std::nan(""), "1"}, {"tiny", 4.9e-324, "deg"}};
  std::string line = sweep::encode_record(41, r);
  EXPECT_EQ(line.find('\n'), std::string::npos);
  size_t idx = 0;
  sweep::PointResult back;
  ASSERT_TRUE(sweep::decode_record(line, idx, back));
  EXPECT_EQ(idx, 41u);
  EXPECT_EQ(back.status, r.status);
  EXPECT_EQ(back.gait_class, "failed");
  ASSERT_EQ(back.features.size(), 3u);
  EXPECT_EQ(std::memcmp(&back.features[0].value, &r.features[0].value, sizeof(double)), 0);
  EXPECT_TRUE(std::isnan(back.features[1].value));
  EXPECT_EQ(back.features[2].value, 4.9e-324);
  EXPECT_EQ(back.features[2].unit, "deg");
  std::string flipped = line;
  flipped[flipped.size() - 3] ^= 1;  // one bit of the payload
  EXPECT_FALSE(sweep::decode_record(flipped, idx, back));
  EXPECT_FALSE(sweep::decode_record(line.substr(0, line.size() / 2), idx, back));
}
