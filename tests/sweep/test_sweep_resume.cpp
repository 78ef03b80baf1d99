// --resume compares everything that determines the result (config/resume_spec.hpp): a changed
// model parameter, --set, trigger or [simulation] key is refused, naming the key, for a journal
// and for a finished file (sweep and gsa); the thread count and the config's spelling are not
// compared. A gsa run leaves no file named OUT without /gsa (docs/gsa.md).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "common/error.hpp"
#include "config/gsa_inputs.hpp"
#include "config/resume_spec.hpp"
#include "config/sweep_inputs.hpp"
#include "io/h5_file.hpp"
#include "sweep/sweep_runner.hpp"

using namespace phasmid;
namespace fs = std::filesystem;

namespace {
// Ishigami at N = 64 (512 points, milliseconds).
const char* kGsa = R"([model]
type = "ishigami"
[parameters]
a = 7.0
b = 0.1
[[sweep.parameter]]
name = "x1"
lower = -3.141592653589793
upper = 3.141592653589793
[[sweep.parameter]]
name = "x2"
lower = -3.141592653589793
upper = 3.141592653589793
[[sweep.parameter]]
name = "x3"
lower = -3.141592653589793
upper = 3.141592653589793
[gsa]
method = "sobol"
N = 64
second_order = false
bootstrap = 20
seed = 1
features = ["y"]
)";

// A plain sweep of the mechanically driven FTi joint with a trigger and a [simulation] key.
const char* kSweep = R"([model]
type = "mechanical_joint"
leg = "middle"
joint = "fti"
[simulation]
t_end_ms = 1000
discard_ms = 200
rtol = 1e-6
[sweep]
[[sweep.parameter]]
name = "middle.fti.b_v"
values = [10.0, 12.5, 16.0]
)";

struct TempDir {
  fs::path path;
  explicit TempDir(const std::string& name)
      : path(fs::temp_directory_path() / ("phasmid_resume_" + name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string operator/(const std::string& leaf) const { return (path / leaf).string(); }
};

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

sweep::SweepOptions options(const std::string& out, int threads, bool resume, long stop_after = -1) {
  sweep::SweepOptions o;
  o.output = out, o.threads = threads, o.resume = resume, o.stop_after = stop_after;
  o.progress = false, o.command = "test";
  return o;
}

gsa::GsaOutcome run_gsa_text(const std::string& text, const std::vector<std::string>& sets, const std::string& out,
                       int threads, bool resume, long stop_after = -1) {
  const gsa::GsaInputs in = config::gsa_inputs(config::parse_config(text, "g.toml"), sets);
  const bool done = resume && !fs::exists(out + ".journal") && fs::exists(out);
  return gsa::run_gsa(in, options(out, threads, resume, stop_after), done);
}

sweep::SweepOutcome sweep_run(const std::string& text, const std::string& out, int threads, bool resume,
                              long stop_after = -1) {
  return sweep::run_sweep(config::sweep_inputs(config::parse_config(text, "s.toml"), {}),
                          options(out, threads, resume, stop_after));
}

// The Error's text, or "" when `f` did not throw.
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(ResumeSpec, SpellingDoesNotCountButEveryResolvedValueDoes) {
  auto spec = [](const std::string& text, const std::vector<std::string>& sets = {}) {
    const auto cfg = config::parse_config(text, "g.toml");
    return config::resume_spec(cfg, config::build_scenario(cfg, sets)->parameters());
  };
  const std::string base = spec(kGsa);
  EXPECT_NE(base.find("model parameter a = 7\n"), std::string::npos) << base;
  EXPECT_EQ(base.find("gsa."), std::string::npos) << "[gsa] is compared as the design's points";
  EXPECT_EQ(spec("# a comment\n" + replaced(kGsa, "a = 7.0", "a = 7")), base);
  EXPECT_EQ(spec(replaced(kGsa, "a = 7.0\nb = 0.1", "b = 0.1\na = 7.0")), base);
  EXPECT_EQ(spec(replaced(kGsa, "bootstrap = 20", "bootstrap = 50")), base);
  EXPECT_EQ(sweep::spec_difference(base, spec(kGsa, {"b=0.5"}), "in OUT"), "model parameter b: 0.1 in OUT, 0.5 now");
  EXPECT_EQ(sweep::spec_difference(base, spec(replaced(kGsa, "a = 7.0", "a = 0.0")), "in OUT"),
            "model parameter a: 7 in OUT, 0 now");
  EXPECT_EQ(sweep::spec_difference(base, base, "in OUT"), "");
}

TEST(ResumeSpec, ATriggerIsPartOfTheSpec) {
  const auto cfg = config::load_config("configs/gait_tripod_to_tetrapod.toml");
  auto changed = config::parse_config(replaced(cfg.text, "after_ms = ", "after_ms = 1"), cfg.path);
  const std::string a = config::resume_spec(cfg, config::build_scenario(cfg)->parameters());
  const std::string b = config::resume_spec(changed, config::build_scenario(changed)->parameters());
  EXPECT_EQ(sweep::spec_difference(a, b, "in OUT").rfind("triggers[0].after_ms: ", 0), 0u) << sweep::spec_difference(a, b, "in OUT");
}

TEST(ResumeSpec, AFinishedGsaFileIsNotRelabelledByAChangedParameterOrSet) {
  TempDir dir("gsa_file");
  const std::string out = dir / "g.h5";
  ASSERT_TRUE(run_gsa_text(kGsa, {}, out, 2, false).analysed);
  const std::string a0 = replaced(kGsa, "a = 7.0", "a = 0.0");
  std::string e = error_of([&] { run_gsa_text(a0, {}, out, 1, true); });
  EXPECT_NE(e.find("the config differs from the one " + out + " was made with (model parameter a: 7 in " + out + ", 0 now)"),
            std::string::npos) << e;
  e = error_of([&] { run_gsa_text(kGsa, {"b=0.5"}, out, 1, true); });
  EXPECT_NE(e.find("(model parameter b: 0.1 in " + out + ", 0.5 now)"), std::string::npos) << e;
  e = error_of([&] { run_gsa_text(replaced(kGsa, "N = 64", "N = 32"), {}, out, 1, true); });
  EXPECT_NE(e.find("design points differ"), std::string::npos) << e;
  // The same config, another thread count and another [gsa] analysis setting: re-analysed.
  EXPECT_TRUE(run_gsa_text(replaced(kGsa, "bootstrap = 20", "bootstrap = 30"), {}, out, 1, true).analysed);
}

TEST(ResumeSpec, AGsaJournalIsNotResumedUnderAChangedParameterOrSet) {
  TempDir dir("gsa_journal");
  const std::string out = dir / "g.h5";
  ASSERT_FALSE(run_gsa_text(kGsa, {}, out, 2, false, 100).analysed);
  std::string e = error_of([&] { run_gsa_text(kGsa, {"a=0"}, out, 1, true); });
  EXPECT_NE(e.find("journal belongs to a different sweep: the config differs from the one it was started with "
                   "(model parameter a: 7 in the journal, 0 now)"),
            std::string::npos) << e;
  EXPECT_FALSE(fs::exists(out));
  const auto rest = run_gsa_text(kGsa, {}, out, 1, true);  // another -j resumes
  ASSERT_TRUE(rest.analysed);
  EXPECT_EQ(rest.sweep.n_recovered, 100u);
  EXPECT_FALSE(fs::exists(out + ".journal"));
  EXPECT_FALSE(fs::exists(gsa::sweep_file_for(out)));
}

TEST(ResumeSpec, ASweepRefusesAChangedSimulationKeyForAJournalAndAFinishedFile) {
  TempDir dir("sweep");
  const std::string out = dir / "s.h5", done = dir / "done.h5";
  ASSERT_FALSE(sweep_run(kSweep, out, 1, false, 1).complete);
  ASSERT_TRUE(sweep_run(kSweep, done, 2, false).complete);
  const std::string rtol = replaced(kSweep, "rtol = 1e-6", "rtol = 1e-7");
  EXPECT_NE(error_of([&] { sweep_run(rtol, out, 1, true); }).find("(simulation.rtol: 1e-06 in the journal, 1e-07 now)"),
            std::string::npos);
  EXPECT_NE(error_of([&] { sweep_run(rtol, done, 1, true); }).find("(simulation.rtol: 1e-06 in " + done + ", 1e-07 now)"),
            std::string::npos);
  EXPECT_TRUE(sweep_run(kSweep, out, 2, true).complete);  // unchanged, another -j
}

TEST(ResumeSpec, AGsaStoppedAfterItsSweepLeavesNoFileWithoutGsa) {
  TempDir dir("no_partial");
  const std::string out = dir / "g.h5";
  // The whole sweep, then the analysis fails (an unreadable sweep file): OUT must not appear.
  const gsa::GsaInputs in = config::gsa_inputs(config::parse_config(kGsa, "g.toml"), {});
  sweep::SweepOptions o = options(out, 1, false);
  o.sweep_file = gsa::sweep_file_for(out), o.keep_journal = true;
  auto s = sweep::run_sweep(in.sweep, o);
  ASSERT_TRUE(s.complete);
  s.kept_journal.reset();  // as if killed here: the journal stays, complete
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(fs::exists(out + ".journal"));
  const auto rest = run_gsa_text(kGsa, {}, out, 2, true);
  ASSERT_TRUE(rest.analysed);
  EXPECT_EQ(rest.sweep.n_computed, 0u);
  EXPECT_TRUE(io::H5Reader(out).exists("/gsa/y"));
  EXPECT_FALSE(fs::exists(gsa::sweep_file_for(out)));

  // A file with /sweep and no /gsa (an older phasmid killed in its analysis): --resume analyses it.
  const std::string old = dir / "old.h5";
  ASSERT_TRUE(sweep::run_sweep(in.sweep, options(old, 2, false)).complete);
  ASSERT_FALSE(io::H5Reader(old).exists("/gsa"));
  ASSERT_TRUE(run_gsa_text(kGsa, {}, old, 1, true).analysed);
  EXPECT_TRUE(io::H5Reader(old).exists("/gsa/y"));
}
