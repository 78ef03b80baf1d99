// Sweep runs: identical datasets for 1 and 2 threads, after interrupt + resume (in-process
// stop and a killed CLI process), failed points recorded with their reason.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

#include "common/error.hpp"
#include "config/sweep_inputs.hpp"
#include "config/sweep_section.hpp"
#include "io/h5_file.hpp"
#include "sweep/sweep_runner.hpp"
#include "build_info.hpp"

extern char** environ;
using namespace phasmid;
namespace fs = std::filesystem;

namespace {
// A 3 x 4 grid on the mechanically driven FTi joint (ms per point) with one deliberately
// failing value: l_E0 = 0.1 mm makes the muscle geometry NaN, so CVODES cannot even start.
const char* kSweep = R"([model]
type = "mechanical_joint"
leg = "middle"
joint = "fti"
[simulation]
t_end_ms = 2000
discard_ms = 500
[sweep]
[[sweep.parameter]]
name = "middle.fti.l_E0"
values = [0.1, 1.35, 1.41]
[[sweep.parameter]]
name = "middle.fti.b_v"
values = [10.0, 12.5, 16.0, 20.0]
)";

// A scratch directory removed with everything in it when the test ends.
struct TempDir {
  fs::path path;
  explicit TempDir(const std::string& name)
      : path(fs::temp_directory_path() / ("phasmid_sweep_" + name + "_" + std::to_string(getpid()))) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  fs::path operator/(const std::string& leaf) const { return path / leaf; }
};

sweep::SweepOutcome run(const config::Config& cfg, const fs::path& out, int threads, bool resume = false,
                        long stop_after = -1) {
  sweep::SweepOptions o;
  o.output = out.string();
  o.threads = threads;
  o.resume = resume;
  o.stop_after = stop_after;
  o.progress = false;
  o.command = "test";
  return sweep::run_sweep(config::sweep_inputs(cfg, {}), o);
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

// Every dataset under /sweep and /parameters equal bit for bit (NaN payloads included).
void expect_identical(const fs::path& a_path, const fs::path& b_path) {
  io::H5Reader a(a_path.string()), b(b_path.string());
  EXPECT_EQ(a.read_strings("/sweep/parameter_names"), b.read_strings("/sweep/parameter_names"));
  EXPECT_TRUE(same_bits(a.read_doubles("/sweep/points"), b.read_doubles("/sweep/points")));
  EXPECT_EQ(a.read_strings("/sweep/status"), b.read_strings("/sweep/status"));
  EXPECT_EQ(a.read_strings("/sweep/gait_class"), b.read_strings("/sweep/gait_class"));
  auto names = a.children("/sweep/features");
  ASSERT_EQ(names, b.children("/sweep/features"));
  ASSERT_FALSE(names.empty());
  for (auto& n : names) {
    EXPECT_TRUE(same_bits(a.read_doubles("/sweep/features/" + n), b.read_doubles("/sweep/features/" + n))) << n;
    EXPECT_EQ(a.read_string_attribute("/sweep/features/" + n, "units"),
              b.read_string_attribute("/sweep/features/" + n, "units"));
  }
  EXPECT_TRUE(same_bits(a.read_doubles("/parameters/values"), b.read_doubles("/parameters/values")));
}

size_t journal_records(const fs::path& journal) {
  std::ifstream in(journal);
  std::string line;
  size_t n = 0;
  while (std::getline(in, line)) ++n;
  return n ? n - 1 : 0;  // minus the header
}
}  // namespace

TEST(SweepRun, FailedPointIsRecordedWithReasonAndSweepFinishes) {
  TempDir dir("fail");
  auto cfg = config::parse_config(kSweep, "sweep_test.toml");
  auto r = run(cfg, dir / "s.h5", 2);
  ASSERT_TRUE(r.complete);
  EXPECT_EQ(r.n_points, 12u);
  EXPECT_EQ(r.n_failed, 4u);
  EXPECT_FALSE(fs::exists(dir / "s.h5.journal")) << "journal removed once the file is complete";
  io::H5Reader h((dir / "s.h5").string());
  auto status = h.read_strings("/sweep/status");
  auto gait = h.read_strings("/sweep/gait_class");
  auto period = h.read_doubles("/sweep/features/period_ms");
  auto points = h.read_doubles("/sweep/points");
  ASSERT_EQ(status.size(), 12u);
  ASSERT_EQ(h.dims("/sweep/points"), (std::vector<hsize_t>{12, 2}));
  for (size_t i = 0; i < 12; ++i) {
    if (points[i * 2] == 0.1) {
      EXPECT_NE(status[i].find("CVODES failed"), std::string::npos) << status[i];
      EXPECT_NE(status[i].find("CV_FIRST_RHSFUNC_ERR"), std::string::npos) << status[i];
      EXPECT_EQ(gait[i], "failed");
      EXPECT_TRUE(std::isnan(period[i]));
    } else {
      EXPECT_EQ(status[i], "ok");
      EXPECT_EQ(gait[i], "ok");
      EXPECT_NEAR(period[i], 500.0, 1.0) << "prescribed 500 ms switching";
    }
  }
  EXPECT_EQ(h.read_string_attribute("/sweep/features/period_ms", "units"), "ms");
  EXPECT_EQ(h.read_strings("/sweep/parameter_units")[1], "g/s");
  EXPECT_EQ(h.read_string_attribute("/", "command"), "test");
  EXPECT_NE(h.read_string_attribute("/", "config").find("[sweep]"), std::string::npos);
}

TEST(SweepRun, OneAndTwoThreadsGiveIdenticalDatasets) {
  TempDir dir("threads");
  auto cfg = config::parse_config(kSweep, "sweep_test.toml");
  auto r1 = run(cfg, dir / "one.h5", 1);
  auto r2 = run(cfg, dir / "two.h5", 2);
  ASSERT_TRUE(r1.complete && r2.complete);
  EXPECT_EQ(r2.threads, 2);
  expect_identical(dir / "one.h5", dir / "two.h5");
}

TEST(SweepRun, InterruptedSweepResumesToTheUninterruptedResult) {
  TempDir dir("resume");
  auto cfg = config::parse_config(kSweep, "sweep_test.toml");
  ASSERT_TRUE(run(cfg, dir / "full.h5", 2).complete);

  auto part = run(cfg, dir / "part.h5", 2, false, 5);
  EXPECT_FALSE(part.complete);
  EXPECT_FALSE(fs::exists(dir / "part.h5")) << "no complete-looking file before all points are done";
  EXPECT_FALSE(fs::exists(dir / "part.h5.tmp"));
  const size_t recorded = journal_records(dir / "part.h5.journal");
  EXPECT_GE(recorded, 5u);
  EXPECT_LT(recorded, 12u);
  // A kill in the middle of a write leaves a torn last line: it must be ignored and recomputed.
  { std::ofstream(dir / "part.h5.journal", std::ios::app) << "0123456789abcdef {\"i\":11,\"s\":\"o"; }

  EXPECT_THROW(run(cfg, dir / "part.h5", 1), Error) << "without --resume an existing journal is not overwritten";
  auto rest = run(cfg, dir / "part.h5", 1, true);
  ASSERT_TRUE(rest.complete);
  EXPECT_EQ(rest.n_recovered, recorded);
  EXPECT_EQ(rest.n_computed, 12u - recorded);
  EXPECT_FALSE(fs::exists(dir / "part.h5.journal"));
  expect_identical(dir / "full.h5", dir / "part.h5");
}

TEST(SweepRun, ASecondSweepOnTheSameJournalIsRefusedWhileTheFirstHoldsIt) {
  TempDir dir("lock");
  auto cfg = config::parse_config(kSweep, "sweep_test.toml");
  auto spec_model = config::build_model(cfg);
  auto spec = sweep::parse_sweep(cfg, spec_model->parameters(), config::simulation_settings(cfg));
  const std::string resolved = config::resolved_config_text(cfg, {});
  sweep::Journal held((dir / "s.h5.journal").string(), sweep::sweep_fingerprint(resolved, spec), spec.n_points, false);
  try {
    run(cfg, dir / "s.h5", 1, true);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("another phasmid sweep is running"), std::string::npos) << e.what();
  }
}

TEST(SweepRun, ResumeRefusesAJournalOfADifferentSweep) {
  TempDir dir("mismatch");
  auto cfg = config::parse_config(kSweep, "sweep_test.toml");
  EXPECT_FALSE(run(cfg, dir / "s.h5", 1, false, 2).complete);
  std::string other = kSweep;
  other.replace(other.find("20.0]"), 5, "21.0]");
  try {
    run(config::parse_config(other, "sweep_test.toml"), dir / "s.h5", 1, true);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("belongs to a different sweep"), std::string::npos) << e.what();
  }
}

TEST(SweepRun, OptionAxesBuildOneModelPerValueAndBadValuesNameTheLine) {
  TempDir dir("options");
  const std::string head = R"([model]
type = "mechanical_joint"
[simulation]
t_end_ms = 2000
discard_ms = 500
[sweep]
[[sweep.option]]
name = "start_phase"
)";
  const std::string tail = R"(
[[sweep.parameter]]
name = "middle.fti.b_v"
values = [10.0, 12.5, 16.0]
)";
  auto cfg = config::parse_config(head + "values = [\"flexion\", \"extension\"]" + tail, "opt.toml");
  auto r = run(cfg, dir / "o.h5", 2);
  ASSERT_TRUE(r.complete);
  EXPECT_EQ(r.n_points, 6u);
  EXPECT_EQ(r.n_failed, 0u);
  io::H5Reader h((dir / "o.h5").string());
  EXPECT_EQ(h.read_strings("/sweep/option_names"), std::vector<std::string>{"start_phase"});
  EXPECT_EQ(h.read_strings("/sweep/options/start_phase"),
            (std::vector<std::string>{"flexion", "flexion", "flexion", "extension", "extension", "extension"}));
  auto fl = h.read_doubles("/sweep/features/middle.fti.flexion_ms");
  EXPECT_EQ(h.read_doubles("/sweep/points"), (std::vector<double>{10, 12.5, 16, 10, 12.5, 16}));
  // The start phase shifts the prescribed switching; the flexion duration must reflect the model built.
  for (size_t i = 0; i < 6; ++i) EXPECT_TRUE(std::isfinite(fl[i])) << i;
  EXPECT_NE(std::memcmp(&fl[0], &fl[3], sizeof(double) * 3), 0) << "flexion- and extension-start runs differ";

  auto bad = config::parse_config(head + "values = [\"flexion\", \"sideways\"]" + tail, "opt.toml");
  try {
    run(bad, dir / "bad.h5", 1);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("opt.toml:9: sweep option start_phase = sideways"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "bad.h5.journal"));
}

#ifdef PHASMID_BINARY
namespace {
pid_t spawn(const std::vector<std::string>& args, const fs::path& err) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  int rc = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  return rc == 0 ? pid : -1;
}

int wait_status(pid_t pid) {
  int st = 0;
  waitpid(pid, &st, 0);
  return st;
}

// Waits until the journal of the sweep running as `pid` holds at least `n` records: "" once
// it does, else why not: the sweep ended first, or no such sign within the hang guard (which
// only catches a hung sweep; it is no limit on how long a point may take).
std::string wait_for_records(pid_t pid, const fs::path& journal, size_t n) {
  const auto hang = std::chrono::steady_clock::now() + std::chrono::seconds(300);
  while (!(fs::exists(journal) && journal_records(journal) >= n)) {
    siginfo_t info{};
    if (waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid)
      return "the sweep ended with " + std::to_string(journal_records(journal)) + " points journalled, before " +
             std::to_string(n);
    if (std::chrono::steady_clock::now() > hang) return "hung: fewer than " + std::to_string(n) + " points journalled after 300 s";
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return "";
}

// Many points of the same work each (a long prescribed-switching run), so that once a few are
// journalled (the sign the signals wait for) most of the sweep is still to come: the signal
// lands mid-sweep whatever the machine's speed, the poll (20 ms) being the only latency.
constexpr size_t kSlowPoints = 80;
const std::string kSlowSweep = R"([model]
type = "mechanical_joint"
leg = "middle"
joint = "fti"
[simulation]
t_end_ms = 60000
discard_ms = 1000
[sweep]
design = "lhs"
points = )" + std::to_string(kSlowPoints) + R"(
seed = 11
[[sweep.parameter]]
name = "middle.fti.b_v"
lower = 8
upper = 20
[[sweep.parameter]]
name = "middle.fti.k_E.flexion"
lower = 400
upper = 600
)";
}  // namespace

TEST(SweepCli, KilledAndInterruptedProcessesResumeToTheUninterruptedResult) {
  TempDir dir("cli");
  const fs::path cfg_path = dir / "slow.toml";
  { std::ofstream(cfg_path) << kSlowSweep; }
  const std::string bin = PHASMID_BINARY, cfg = cfg_path.string();
  const fs::path out = dir / "cli.h5", journal = dir / "cli.h5.journal";

  // 1. SIGKILL once 3 points are journalled: no chance to clean up; the journal alone must
  // carry the finished points.
  pid_t pid = spawn({bin, "sweep", cfg, "-o", out.string(), "-j", "2", "-q"}, dir / "err1");
  ASSERT_GT(pid, 0);
  std::string why = wait_for_records(pid, journal, 3);
  kill(pid, SIGKILL);
  int st = wait_status(pid);
  ASSERT_EQ(why, "");
  ASSERT_TRUE(WIFSIGNALED(st)) << "the sweep of " << kSlowPoints << " points ended by itself";
  EXPECT_FALSE(fs::exists(out));
  const size_t after_kill = journal_records(journal);
  ASSERT_LT(after_kill, kSlowPoints) << "every point was done before SIGKILL";

  // 2. SIGINT (Ctrl-C) on the resumed run once 3 more points are journalled: finishes the
  // running points, says how to resume, exit 130.
  pid = spawn({bin, "sweep", cfg, "-o", out.string(), "-j", "2", "-q", "--resume"}, dir / "err2");
  ASSERT_GT(pid, 0);
  why = wait_for_records(pid, journal, after_kill + 3);
  kill(pid, why.empty() ? SIGINT : SIGKILL);
  st = wait_status(pid);
  ASSERT_EQ(why, "");
  ASSERT_TRUE(WIFEXITED(st)) << "the sweep did not exit after SIGINT";
  EXPECT_EQ(WEXITSTATUS(st), 130) << "the sweep of " << kSlowPoints << " points was not interrupted";
  std::ifstream e(dir / "err2");
  std::string msg((std::istreambuf_iterator<char>(e)), {});
  EXPECT_NE(msg.find("--resume"), std::string::npos) << msg;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_GT(journal_records(journal), after_kill);
  EXPECT_LT(journal_records(journal), kSlowPoints);

  // 3. Resume to the end, single-threaded this time, and compare with one uninterrupted run.
  pid = spawn({bin, "sweep", cfg, "-o", out.string(), "-j", "1", "-q", "--resume"}, dir / "err3");
  ASSERT_EQ(WEXITSTATUS(wait_status(pid)), 0);
  EXPECT_FALSE(fs::exists(journal));
  auto c = config::load_config(cfg);
  ASSERT_TRUE(run(c, dir / "ref.h5", 2).complete);
  expect_identical(dir / "ref.h5", out);
}
#endif
