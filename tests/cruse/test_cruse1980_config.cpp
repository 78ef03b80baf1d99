// Cruse (1980) configs ([model] type = "cruse1980") and `phasmid simulate` on them: errors name file, line and key; the HDF5
// file has the documented layout.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "common/error.hpp"
#include "config/config.hpp"
#include "cruse/cruse1980_parameters.hpp"
#include "io/h5_file.hpp"
#include "build_info.hpp"

using namespace phasmid::cruse;
namespace fs = std::filesystem;

namespace {

std::string write_temp(const std::string& name, const std::string& text) {
  const auto path = (fs::temp_directory_path() / name).string();
  std::ofstream(path) << text;
  return path;
}

std::string error_of(const std::string& path) {
  try {
    phasmid::config::build_scenario(phasmid::config::load_config(path));
  } catch (const phasmid::Error& e) {
    return e.what();
  }
  return "";
}

// A cruse1980 scenario's parameter value by name.
double value_of(const std::string& config, const std::string& name, const std::vector<std::string>& sets = {}) {
  return phasmid::config::build_scenario(phasmid::config::load_config(config), sets)->parameters().value(name);
}

}  // namespace

TEST(Cruse1980Config, EmbeddedConfigsLoad) {
  auto g2 = phasmid::config::build_scenario(phasmid::config::load_config("configs/cruse1980_gait2.toml"));
  EXPECT_EQ(g2->kind(), "cruse1980");
  EXPECT_DOUBLE_EQ(g2->parameters().value("T0.R2"), 10.3);
  EXPECT_DOUBLE_EQ(g2->parameters().value("switch.SL.at_1000ms"), 6.67);
  EXPECT_DOUBLE_EQ(value_of("cruse1980_gait1", "gait1.protraction_to_retraction_rate"), 1.5);
  // Gait I: 10 / (1/60) + 10 / (1.5/60) = 600 + 400 ms, the period the run measures.
  auto g1 = phasmid::config::build_scenario(phasmid::config::load_config("cruse1980_gait1"));
  const auto features = g1->evaluate_features(g1->parameters().values(), {});
  const auto period = std::find_if(features.begin(), features.end(), [](auto& f) { return f.name == "period_ms"; });
  ASSERT_NE(period, features.end());
  EXPECT_NEAR(period->value, 1000.0, 1e-6);
}

TEST(Cruse1980Config, UnknownParameterNamesFileLineAndKey) {
  const auto path = write_temp("cruse_bad_key.toml", "[model]\ntype = \"cruse1980\"\n[parameters]\nT1 = 7\nT3 = 2\n");
  const auto msg = error_of(path);
  EXPECT_NE(msg.find(path + ":5"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'T3'"), std::string::npos) << msg;
}

TEST(Cruse1980Config, OldTopLevelFormSaysWhatToWrite) {
  const auto path = write_temp("cruse_old.toml", "model = \"cruse1980\"\n[cruse1980]\nT1 = 7\n");
  const auto msg = error_of(path);
  EXPECT_NE(msg.find(path + ":1"), std::string::npos) << msg;
  EXPECT_NE(msg.find("[model] with type = \"cruse1980\""), std::string::npos) << msg;
}

TEST(Cruse1980Config, UnknownKeysInOtherSectionsAreIgnored) {
  const auto path = write_temp("cruse_other.toml",
                               "[model]\ntype = \"cruse1980\"\n[fit]\nanything = 3\n[parameters]\nT2 = 4.0\n");
  EXPECT_DOUBLE_EQ(value_of(path, "T2"), 4.0);
}

TEST(Cruse1980Config, StartPositionOutsideTable2IsRejected) {
  const auto path = write_temp("cruse_start.toml", "[model]\ntype = \"cruse1980\"\n[parameters]\nstart_position = 11\n");
  const auto msg = error_of(path);
  EXPECT_NE(msg.find(path + ":4"), std::string::npos) << msg;
  EXPECT_NE(msg.find("start_position"), std::string::npos) << msg;
}

TEST(Cruse1980Config, SimulationSectionDoesNotApply) {
  const auto path = write_temp("cruse_sim.toml", "[model]\ntype = \"cruse1980\"\n[simulation]\nt_end_ms = 5\n");
  auto cfg = phasmid::config::load_config(path);
  auto s = phasmid::config::build_scenario(cfg);
  try {
    phasmid::config::simulation_settings(cfg, s.get());
    ADD_FAILURE() << "[simulation] accepted for cruse1980";
  } catch (const phasmid::Error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":3: [simulation] does not apply"), std::string::npos) << e.what();
  }
}

TEST(Cruse1980Config, Table2RowsAsPrinted) {
  // Position 9: OL1 3, OL2 5, OL3 7, OR1 3, OR2 5, OR3 7.
  const auto s = table2_start(9);
  EXPECT_EQ(s[L1], 3);
  EXPECT_EQ(s[L2], 5);
  EXPECT_EQ(s[L3], 7);
  EXPECT_EQ(s[R1], 3);
  EXPECT_EQ(s[R2], 5);
  EXPECT_EQ(s[R3], 7);
  EXPECT_EQ(table2_start(10)[R2], 10);
}

TEST(Cruse1980Config, SetOverridesAndRejectsUnknownNames) {
  EXPECT_DOUBLE_EQ(value_of("cruse1980_gait2", "T1", {"T1=6.5"}), 6.5);
  EXPECT_THROW(value_of("cruse1980_gait2", "T1", {"T9=1"}), phasmid::Error);
  EXPECT_THROW(value_of("cruse1980_gait2", "T1", {"T1=abc"}), phasmid::Error);
}

TEST(Cruse1980Cli, WritesDocumentedHdf5Layout) {
  const auto out = (fs::temp_directory_path() / "cruse_cli.h5").string();
  fs::remove(out);
  const std::string cmd = std::string(PHASMID_BINARY) + " simulate configs/cruse1980_gait2.toml -q -o " + out +
                          " --set start_position=7 > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  phasmid::io::H5Reader r(out);
  EXPECT_EQ(r.read_string_attribute("/trajectory/time", "units"), "ms");
  const auto time = r.read_doubles("/trajectory/time");
  EXPECT_EQ(time.size(), 1501u);  // 30 s on the 20 ms raster
  for (const char* leg : {"L1", "L2", "L3", "R1", "R2", "R3"}) {
    EXPECT_EQ(r.read_doubles(std::string("/trajectory/position/") + leg).size(), time.size());
    EXPECT_EQ(r.read_string_attribute(std::string("/trajectory/protraction/") + leg, "units"), "1");
  }
  EXPECT_NEAR(r.read_doubles("/features/period_ms")[0], 1000.0, 1e-9);
  const auto pairs = r.read_strings("/features/in_phase_pairs");
  EXPECT_NE(std::find(pairs.begin(), pairs.end(), "L1-R2"), pairs.end());
  EXPECT_EQ(r.read_strings("/parameters/names").size(), r.read_doubles("/parameters/values").size());
  EXPECT_FALSE(r.read_string_attribute("/", "command").empty());
}

TEST(Cruse1980Cli, BadConfigExitsNonZero) {
  const auto path = write_temp("cruse_cli_bad.toml", "[model]\ntype = \"cruse1980\"\n[parameters]\nbogus = 1\n");
  const std::string cmd = std::string(PHASMID_BINARY) + " simulate " + path + " 2> /dev/null";
  EXPECT_NE(std::system(cmd.c_str()), 0);
}
