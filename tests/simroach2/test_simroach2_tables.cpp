// SimRoach2 Tables 1-5 as transcribed, and the Table 3 consistency check over all 60 muscles.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "common/error.hpp"
#include "simroach2/muscle_check.hpp"
#include "simroach2/tables.hpp"
#include "build_info.hpp"

using namespace phasmid::simroach2;

TEST(SimRoach2Tables, AllFiveTablesHaveThirtyJoints) {
  for (const char* f : {"table1_rest_lengths.csv", "table2_spring_stiffness_damping.csv", "table3_muscle_activation.csv",
                        "table4_pi_synapses.csv", "table5_upper_level_synapses.csv"})
    EXPECT_EQ(load_table(f).rows.size(), 30u) << f;
}

TEST(SimRoach2Tables, SpotValuesAsPrinted) {
  const auto t1 = load_table("table1_rest_lengths.csv");
  EXPECT_EQ(t1.text(16, "joint"), "ThC1");  // RM ThC1
  EXPECT_EQ(t1.text(16, "extensor_rest_length_mm"), "3.84");
  const auto t2 = load_table("table2_spring_stiffness_damping.csv");
  EXPECT_DOUBLE_EQ(t2.number(22, "damping_mg_per_s"), 23.78);  // LH CTr
  EXPECT_DOUBLE_EQ(t2.number(21, "stiffness_N_per_m"), 2677.0);  // LH ThC1
  const auto t4 = load_table("table4_pi_synapses.csv");
  EXPECT_DOUBLE_EQ(t4.number(29, "integral_conductance_uS"), 19.067);  // RH FTi
  EXPECT_DOUBLE_EQ(t4.number(29, "proportional_conductance_uS"), 2.415);
  const auto t5 = load_table("table5_upper_level_synapses.csv");
  EXPECT_EQ(t5.text(28, "reversed_synapses"), "Rotation and Translation");  // RH TrF
  EXPECT_DOUBLE_EQ(t5.number(28, "rotational_conductance_nS"), 0.029212);
}

TEST(SimRoach2Tables, MalformedCsvNamesLine) {
  try {
    parse_table("# c\na,b\n1,2\n3\n", "x.csv");
    FAIL();
  } catch (const phasmid::Error& e) {
    EXPECT_NE(std::string(e.what()).find("x.csv:4"), std::string::npos) << e.what();
  }
  EXPECT_EQ(printed_decimals("1.00"), 2);
  EXPECT_EQ(printed_decimals("-143.0"), 1);
  EXPECT_EQ(printed_decimals("10"), 0);
}

// Sect. 2.3 says every y-offset makes the active force zero at -60 mV. Computed from the
// printed values, 51 of the 60 muscles satisfy that to printing precision; 9 do not.
TEST(SimRoach2MuscleCheck, SixtyMusclesNineInconsistent) {
  const auto rows = check_muscles(load_table("table3_muscle_activation.csv"));
  ASSERT_EQ(rows.size(), 60u);
  std::set<std::string> inconsistent;
  for (const auto& r : rows)
    if (!r.consistent) inconsistent.insert(r.joint + " " + r.muscle);
  const std::set<std::string> expected{"LM ThC1 flexor",  "LM ThC1 extensor", "LM CTr extensor",
                                       "LM TrF extensor", "LH ThC2 flexor",   "LH ThC1 extensor",
                                       "LH TrF flexor",   "RH ThC1 extensor", "RH TrF flexor"};
  EXPECT_EQ(inconsistent, expected);
  // LM ThC1 flexor: 1000 mN * 0.0474259 - 50.00 mN = -2.574 mN (y-offset = -5 % of amplitude).
  for (const auto& r : rows)
    if (r.joint == "LM ThC1" && r.muscle == "flexor") EXPECT_NEAR(r.force_at_rest_mN, -2.574126827, 1e-6);
  // RH TrF flexor: 1211 * 0.04742587 - 52.166 = 57.43273 - 52.166 = +5.26673 mN, the largest.
  for (const auto& r : rows)
    if (r.joint == "RH TrF" && r.muscle == "flexor") EXPECT_NEAR(r.force_at_rest_mN, 5.266732418, 1e-6);
}

// The CLI finds the embedded tables from any working directory.
TEST(SimRoach2Cli, CheckMusclesJson) {
  const auto out = (std::filesystem::temp_directory_path() / "simroach2_check.json").string();
  const std::string cmd = "cd / && " + std::string(PHASMID_BINARY) + " simroach2 check-muscles --json > " + out;
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::ifstream in(out);
  const auto j = nlohmann::json::parse(in);
  ASSERT_EQ(j.size(), 60u);
  int consistent = 0;
  for (const auto& row : j) {
    for (const char* key : {"joint", "muscle", "amplitude_N", "y_offset_mN", "force_at_rest_mN", "consistent"})
      EXPECT_TRUE(row.contains(key)) << key;
    consistent += row["consistent"].get<bool>();
  }
  EXPECT_EQ(consistent, 51);
  EXPECT_EQ(j[0]["joint"], "LF ThC2");
  EXPECT_EQ(j[0]["muscle"], "flexor");
}
