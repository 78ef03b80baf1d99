// The checks every verb's inputs and outputs go through (docs/reliability.md): output paths
// (io::check_output_path), bounded text reads (io::read_text_file) and the bounds of a run's
// times (config::check_run_times), each at its documented limit.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <fstream>

#include "common/error.hpp"
#include "config/toml_util.hpp"
#include "io/output_path.hpp"
#include "io/text_file.hpp"

namespace fs = std::filesystem;
using phasmid::Error;

namespace {
struct TempDir {
  fs::path p = fs::temp_directory_path() / ("phasmid_io_checks_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(p); }
  ~TempDir() { fs::remove_all(p); }
};

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(OutputPath, NewPathsAndRegularFilesAreAccepted) {
  TempDir d;
  EXPECT_EQ(error_of([&] { phasmid::io::check_output_path((d.p / "new.h5").string()); }), "");
  std::ofstream(d.p / "old.h5") << "x";
  EXPECT_EQ(error_of([&] { phasmid::io::check_output_path((d.p / "old.h5").string(), {(d.p / "in.toml").string()}); }), "");
}

TEST(OutputPath, DevicesDirectoriesAndFifosAreRefusedAlsoThroughSymlinks) {
  TempDir d;
  fs::create_symlink("/dev/null", d.p / "null");
  fs::create_directory(d.p / "dir");
  ASSERT_EQ(::mkfifo((d.p / "fifo").c_str(), 0600), 0);
  EXPECT_NE(error_of([&] { phasmid::io::check_output_path((d.p / "null").string()); }).find("is a character device"),
            std::string::npos);
  EXPECT_NE(error_of([&] { phasmid::io::check_output_path((d.p / "dir").string()); }).find("is a directory"),
            std::string::npos);
  EXPECT_NE(error_of([&] { phasmid::io::check_output_path((d.p / "fifo").string()); }).find("is a fifo"),
            std::string::npos);
  fs::create_directory(d.p / "x.h5.tmp");  // the temporary companion is checked too
  EXPECT_NE(error_of([&] { phasmid::io::check_output_path((d.p / "x.h5").string()); }).find("x.h5.tmp is a directory"),
            std::string::npos);
}

TEST(OutputPath, AnInputByAnyNameIsRefused) {
  TempDir d;
  const fs::path in = d.p / "in.toml";
  std::ofstream(in) << "[model]\n";
  fs::create_hard_link(in, d.p / "hard.h5");
  fs::create_symlink(in, d.p / "soft.h5");
  for (const char* out : {"hard.h5", "soft.h5", "./in.toml"}) {
    const std::string msg = error_of([&] { phasmid::io::check_output_path((d.p / out).string(), {in.string()}); });
    EXPECT_NE(msg.find("is the input " + in.string()), std::string::npos) << out << ": " << msg;
  }
  // an input that does not exist on disk (an embedded config) is no conflict
  EXPECT_EQ(error_of([&] { phasmid::io::check_output_path((d.p / "o.h5").string(), {"configs/x.toml"}); }), "");
}

TEST(TextFile, ReadsRegularFilesUpToTheLimitOnly) {
  TempDir d;
  std::ofstream(d.p / "a.csv") << "time_ms,middle.fti\n0,45\n";
  EXPECT_EQ(phasmid::io::read_text_file((d.p / "a.csv").string(), "data"), "time_ms,middle.fti\n0,45\n");
  EXPECT_NE(error_of([] { phasmid::io::read_text_file("/dev/zero", "data"); }).find("/dev/zero: cannot read data: not a regular file"),
            std::string::npos);
  const fs::path big = d.p / "big.csv";
  std::ofstream(big).close();
  fs::resize_file(big, phasmid::io::kMaxTextInputBytes);  // sparse: exactly the limit is read
  EXPECT_EQ(phasmid::io::read_text_file(big.string(), "data").size(), phasmid::io::kMaxTextInputBytes);
  fs::resize_file(big, phasmid::io::kMaxTextInputBytes + 1);
  EXPECT_NE(error_of([&] { phasmid::io::read_text_file(big.string(), "data"); }).find("67108865 bytes, more than the limit of 67108864"),
            std::string::npos);
}

TEST(RunTimes, BoundsAreInclusiveAtTheDocumentedLimits) {
  using phasmid::config::check_run_times;
  EXPECT_EQ(error_of([] { check_run_times(1e7, 1.0, 0, "f"); }), "");       // 1e7 ms, 1e7 samples
  EXPECT_EQ(error_of([] { check_run_times(10, 1e-3, 0, "f"); }), "");       // the finest grid
  EXPECT_NE(error_of([] { check_run_times(1e7 + 1, 10.0, 0, "f"); }).find("f: t_end_ms = 10000001 must be in (0, 10000000] ms"),
            std::string::npos);
  EXPECT_NE(error_of([] { check_run_times(10, 9e-4, 0, "f"); }).find("output_dt_ms = 0.0009 must be in [0.001, t_end_ms]"),
            std::string::npos);
  EXPECT_NE(error_of([] { check_run_times(1e7, 0.999, 0, "f"); }).find("= 10010010.01 samples; at most 10000000"), std::string::npos);
  EXPECT_EQ(error_of([] { check_run_times(1e7, 0.999, 1e4, "f"); }), "");  // discarded time is not stored
  EXPECT_NE(error_of([] { check_run_times(10, 1, 10, "f"); }).find("discard_ms = 10 must be in [0, t_end_ms = 10)"),
            std::string::npos);
  EXPECT_NE(error_of([] { check_run_times(NAN, 1, 0, "f"); }).find("t_end_ms = nan"), std::string::npos);
}
