// HDF5 layer: datasets carry units, files appear only after commit().
#include <gtest/gtest.h>

#include <filesystem>

#include "common/error.hpp"
#include "io/h5_file.hpp"

using namespace phasmid::io;

TEST(H5File, RoundTripWithUnitsAndAtomicCommit) {
  auto path = (std::filesystem::temp_directory_path() / "phasmid_h5_roundtrip.h5").string();
  std::filesystem::remove(path);
  {
    H5Writer w(path);
    w.write_run_info({"a = 1\n", "phasmid test"});
    w.write("/trajectory/time", std::vector<double>{0.0, 1.5, 3.0}, "ms");
    w.write("/parameters/names", std::vector<std::string>{"middle.fti.b_v", "x"});
    w.write_scalar("/features/period_ms", 510.0, "ms");
    EXPECT_FALSE(std::filesystem::exists(path)) << "final name must not exist before commit";
    w.commit();
  }
  H5Reader r(path);
  EXPECT_EQ(r.read_doubles("/trajectory/time"), (std::vector<double>{0.0, 1.5, 3.0}));
  EXPECT_EQ(r.read_string_attribute("/trajectory/time", "units"), "ms");
  EXPECT_EQ(r.read_strings("/parameters/names")[0], "middle.fti.b_v");
  EXPECT_DOUBLE_EQ(r.read_doubles("/features/period_ms")[0], 510.0);
  EXPECT_EQ(r.read_string_attribute("/", "config"), "a = 1\n");
  EXPECT_TRUE(r.is_group("/trajectory"));
  EXPECT_FALSE(r.exists("/nothing/here"));
}

TEST(H5File, UncommittedWriterLeavesNoFile) {
  auto path = (std::filesystem::temp_directory_path() / "phasmid_h5_abandoned.h5").string();
  std::filesystem::remove(path);
  { H5Writer w(path); w.write_scalar("/x", 1.0, "1"); }
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}
