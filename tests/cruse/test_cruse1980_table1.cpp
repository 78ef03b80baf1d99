// Cruse (1980) Table 1 as a `phasmid sweep` of the cruse1980 kind (configs/cruse1980_table1.toml):
// the one-at-a-time sweep of T0 (OL2..OR3), T1 and T2 with its range analysis. The expected
// ranges are those the former dedicated verb (`cruse-sweep`, removed when Cruse became a model
// kind) printed on the same grids; docs/cruse1980.md compares them with Table 1.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "config/sweep_inputs.hpp"
#include "io/h5_file.hpp"
#include "sweep/ranges.hpp"
#include "sweep/sweep_runner.hpp"
#include "build_info.hpp"

using namespace phasmid;
namespace fs = std::filesystem;

TEST(Cruse1980Table1, SweepReproducesTheStabilityRanges) {
  const config::Config cfg = config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/cruse1980_table1.toml");
  const fs::path out = fs::temp_directory_path() / ("table1_" + std::to_string(getpid()) + ".h5");
  sweep::SweepOptions o;
  o.output = out.string();
  o.progress = false;
  ASSERT_TRUE(sweep::run_sweep(config::sweep_inputs(cfg, {}), o).complete);
  io::H5Reader r(out.string());
  const auto ranges = sweep::read_ranges_h5(r);
  ASSERT_EQ(ranges.size(), 7u);
  struct Expected {
    const char* parameter;
    double lower, upper;
    bool contiguous;
  };
  // T0 of OL2..OR3 stable from 10.05 (just above OL1's 10) up to the end of the grid; T1 from 4.5
  // to 9.25 (Table 1: 5-9); T2 over the whole grid but for 9.75 and 10 (Table 1: 1-10).
  const Expected want[] = {{"T0.L2", 10.05, 10.8, true}, {"T0.L3", 10.05, 10.8, true}, {"T0.R1", 10.05, 10.8, true},
                           {"T0.R2", 10.05, 10.8, true}, {"T0.R3", 10.05, 10.8, true}, {"T1", 4.5, 9.25, true},
                           {"T2", 0.25, 11.0, false}};
  for (size_t k = 0; k < 7; ++k) {
    SCOPED_TRACE(want[k].parameter);
    EXPECT_EQ(ranges[k].parameter, want[k].parameter);
    EXPECT_DOUBLE_EQ(ranges[k].lower, want[k].lower);
    EXPECT_DOUBLE_EQ(ranges[k].upper, want[k].upper);
    EXPECT_EQ(ranges[k].contiguous, want[k].contiguous);
  }
  // the gap of T2: exactly 9.75 and 10.0 fail
  const auto& t2 = ranges[6];
  for (size_t i = 0; i < t2.values.size(); ++i)
    EXPECT_EQ(t2.in_range[i], (t2.values[i] == 9.75 || t2.values[i] == 10.0) ? 0 : 1) << t2.values[i];
  fs::remove(out);
}
