// `phasmid report`: extraction unit tests, CLI behaviour, and every kind of report rendered in
// headless Chromium (Debian's chromium) with no script errors and the expected figures.
//
// Chromium is required: without it the rendering tests FAIL (CI installs it, scripts/setup.sh).
// Set PHASMID_SCREENSHOT_DIR=docs to also write docs/report_<kind>.png.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "common/error.hpp"
#include "gsa/gsa_h5.hpp"
#include "gsa/resolution.hpp"
#include "report/report.hpp"
#include "report_fixtures.hpp"
#include "build_info.hpp"

namespace fs = std::filesystem;
using phasmid::report::extract;

namespace {

struct Result {
  int code;
  std::string out;
};

Result run(const std::string& cmd) {
  Result r{-1, ""};
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  int st = pclose(p);
  r.code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string q(const std::string& s) { return "'" + s + "'"; }

fs::path work_dir() {
  static fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("phasmid_report_test_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

std::string chromium() {
  if (const char* c = std::getenv("PHASMID_CHROMIUM")) return c;
  for (const char* c : {"/usr/bin/chromium", "/usr/bin/chromium-browser"})
    if (fs::exists(c)) return c;
  return "";
}

std::string chromium_cmd(const std::string& extra, const fs::path& profile) {
  return q(chromium()) +
         " --headless --no-sandbox --disable-gpu --disable-dev-shm-usage --disable-background-networking"
         " --disable-component-update --disable-sync --no-first-run --no-default-browser-check"
         " --user-data-dir=" +
         q(profile.string()) + " --enable-logging=stderr --v=0 --virtual-time-budget=15000 " + extra;
}

struct Page {
  std::string dom, log;
  std::string attr(const std::string& name) const {
    std::smatch m;
    std::regex re("<body[^>]*\\s" + name + "=\"([^\"]*)\"");
    return std::regex_search(dom, m, re) ? m[1].str() : std::string("<missing>");
  }
  std::set<std::string> figures() const {
    std::set<std::string> s;
    std::istringstream in(attr("data-figures"));
    for (std::string w; in >> w;) s.insert(w);
    return s;
  }
  // Every console message (the page logs nothing when all is well) and uncaught exceptions,
  // as Chromium logs them with --enable-logging=stderr.
  std::vector<std::string> console_errors() const {
    std::vector<std::string> out;
    std::istringstream in(log);
    for (std::string line; std::getline(in, line);) {
      if (line.find(":CONSOLE") != std::string::npos || line.find("Uncaught") != std::string::npos)
        out.push_back(line);
    }
    return out;
  }
};

Page load(const fs::path& html) {
  fs::path profile = work_dir() / ("profile_" + html.stem().string());
  fs::create_directories(profile);
  fs::path err = work_dir() / (html.stem().string() + ".chromium.log");
  Result r = run(chromium_cmd("--dump-dom " + q("file://" + fs::absolute(html).string()), profile) + " 2>" +
                 q(err.string()));
  Page p{r.out, slurp(err)};
  return p;
}

// Writes the report of `h5` with the CLI and returns the HTML path.
fs::path make_report(const fs::path& h5) {
  fs::path html = work_dir() / (h5.stem().string() + ".html");
  Result r = run(q(PHASMID_BINARY) + " report " + q(h5.string()) + " -o " + q(html.string()) + " 2>&1");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(fs::exists(html)) << r.out;
  return html;
}

void maybe_screenshot(const fs::path& html, const std::string& kind) {
  const char* dir = std::getenv("PHASMID_SCREENSHOT_DIR");
  if (!dir) return;
  fs::create_directories(dir);
  fs::path png = fs::absolute(fs::path(dir) / ("report_" + kind + ".png"));
  fs::path profile = work_dir() / ("shot_" + kind);
  fs::create_directories(profile);
  run(chromium_cmd("--hide-scrollbars --window-size=1200,2000 --screenshot=" + q(png.string()) + " " +
                       q("file://" + fs::absolute(html).string()),
                   profile) +
      " >/dev/null 2>&1");
  EXPECT_TRUE(fs::exists(png)) << png;
}

void expect_renders(const std::string& kind, const fs::path& h5, const std::vector<std::string>& expected,
                    const std::vector<std::string>& absent = {}, bool screenshot = true) {
  ASSERT_FALSE(chromium().empty()) << "chromium is required for the report rendering tests "
                                      "(apt-get install -y chromium; see scripts/setup.sh)";
  fs::path html = make_report(h5);
  Page page = load(html);
  ASSERT_NE(page.dom.find("<body"), std::string::npos) << "chromium returned no DOM; log:\n" << page.log;
  EXPECT_EQ(page.attr("data-status"), "ok") << "errors: " << page.attr("data-errors");
  EXPECT_EQ(page.attr("data-errors"), "");
  auto errs = page.console_errors();
  EXPECT_TRUE(errs.empty()) << errs.size() << " console errors, first: " << (errs.empty() ? "" : errs[0]);
  auto figs = page.figures();
  for (const auto& id : expected) {
    EXPECT_TRUE(figs.count(id)) << kind << ": figure " << id << " not rendered; rendered: " << page.attr("data-figures");
    // A rendered figure is a real element with a drawn canvas (or a table) in the DOM.
    EXPECT_NE(page.dom.find("id=\"" + id + "\""), std::string::npos) << id;
  }
  for (const auto& id : absent) EXPECT_FALSE(figs.count(id)) << kind << ": unexpected figure " << id;
  if (screenshot) maybe_screenshot(html, kind);
}

// Removes the scratch directory at the end unless PHASMID_KEEP_TEST_FILES is set.
class CleanUp : public ::testing::Environment {
 public:
  void TearDown() override {
    if (std::getenv("PHASMID_KEEP_TEST_FILES")) {
      std::printf("report test files kept in %s\n", work_dir().c_str());
      return;
    }
    std::error_code ec;
    fs::remove_all(work_dir(), ec);
  }
};
const auto* const clean_up = ::testing::AddGlobalTestEnvironment(new CleanUp);

}  // namespace

// ------------------------------------------------------------------ unit tests

TEST(ReportUnits, DecimationKeepsEndsAndPeaks) {
  std::vector<double> y(100000, 0.0);
  y[12345] = 50.0;  // a single-sample spike
  y[77777] = -40.0;
  auto idx = phasmid::report::decimate_indices(y, 5000);
  EXPECT_LE(idx.size(), 5000u);
  EXPECT_EQ(idx.front(), 0u);
  EXPECT_EQ(idx.back(), y.size() - 1);
  EXPECT_TRUE(std::is_sorted(idx.begin(), idx.end()));
  EXPECT_NE(std::find(idx.begin(), idx.end(), 12345u), idx.end());
  EXPECT_NE(std::find(idx.begin(), idx.end(), 77777u), idx.end());
  auto small = phasmid::report::decimate_indices(std::vector<double>(10, 1.0), 5000);
  EXPECT_EQ(small.size(), 10u);
}

TEST(ReportUnits, SwingIntervals) {
  std::vector<double> t = {0, 1, 2, 3, 4, 5, 6};
  std::vector<double> f = {1, 1, 0, 0, 1, 0, 1};
  auto iv = phasmid::report::intervals_where(t, f);
  ASSERT_EQ(iv.size(), 3u);
  EXPECT_EQ(iv[0], std::make_pair(0.0, 2.0));
  EXPECT_EQ(iv[1], std::make_pair(4.0, 5.0));
  EXPECT_EQ(iv[2], std::make_pair(6.0, 6.0));
}

TEST(ReportUnits, JsonForScriptCannotCloseTheScriptTag) {
  nlohmann::json j = {{"config", "x = \"</script><script>alert(1)</script>\""}};
  std::string s = phasmid::report::json_for_script(j);
  EXPECT_EQ(s.find('<'), std::string::npos);
  EXPECT_EQ(nlohmann::json::parse(s), j);
}

TEST(ReportUnits, ExtractTrajectoryFindsGroupsAndDecimates) {
  fs::path h5 = work_dir() / "unit_trajectory.h5";
  phasmid::testing::write_trajectory_fixture(h5.string());
  auto j = extract(h5.string());
  ASSERT_TRUE(j.contains("trajectory"));
  const auto& tr = j["trajectory"];
  EXPECT_EQ(tr["angles"].size(), 9u);
  EXPECT_EQ(tr["angles"][0]["leg"], "front");
  EXPECT_EQ(tr["angles"][0]["joint"], "thc");
  EXPECT_EQ(tr["angles"][0]["units"], "deg");
  EXPECT_TRUE(tr["decimated"].get<bool>());
  EXPECT_LE(tr["angles"][0]["y"].size(), 5000u);
  EXPECT_EQ(tr["angles"][0]["t"].size(), tr["angles"][0]["y"].size());
  EXPECT_EQ(tr["voltages"].size(), 13u);  // C1, C2, MN1, MN2 .V of three joints, one interneuron
  for (const auto& v : tr["voltages"]) {
    const auto name = v["name"].get<std::string>();
    EXPECT_EQ(v["kind"], name == "middle.fti.in_ext.V" ? "other" : "cpg_mn") << name;
  }
  EXPECT_EQ(tr["other_states"].size(), 12u);  // the .w states are listed, not drawn
  EXPECT_EQ(tr["footfall"].size(), 3u);
  EXPECT_GE(tr["footfall"][1]["intervals"].size(), 2u);
  EXPECT_EQ(j["features"].size(), 5u);
  EXPECT_EQ(j["parameters"].size(), 4u);
  EXPECT_EQ(j["parameters"][2]["units"], "mN mm s/deg");
  EXPECT_EQ(j["attrs"]["command"], "phasmid test-fixture trajectory");
  bool ignored = false;
  for (auto& p : j["ignored"]) ignored |= p.get<std::string>() == "/unknown_extension";
  EXPECT_TRUE(ignored);
}

TEST(ReportUnits, ExtractSweepShapes) {
  fs::path h5 = work_dir() / "unit_sweep.h5";
  phasmid::testing::write_sweep_fixture(h5.string());
  auto j = extract(h5.string());
  const auto& s = j["sweep"];
  EXPECT_EQ(s["points"].size(), 32u);
  EXPECT_EQ(s["points"][0].size(), 3u);
  EXPECT_EQ(s["features"].size(), 2u);
  EXPECT_TRUE(s["features"][0]["values"][5].is_null());  // the failed point's NaN
  EXPECT_EQ(s["status"][5], "CVODE: too much work at t = 312 ms");
}

TEST(ReportUnits, MissingOrNonHdf5FileIsAOneLineError) {
  EXPECT_THROW(extract((work_dir() / "nope.h5").string()), phasmid::Error);
  fs::path bad = work_dir() / "not_hdf5.h5";
  std::ofstream(bad) << "this is not HDF5\n";
  try {
    extract(bad.string());
    FAIL() << "no error";
  } catch (const phasmid::Error& e) {
    EXPECT_NE(std::string(e.what()).find("not an HDF5 file"), std::string::npos);
  }
}

// ------------------------------------------------------------------ CLI

TEST(ReportCli, DefaultOutputNextToInputAndErrors) {
  fs::path dir = work_dir() / "cli";
  fs::create_directories(dir);
  fs::path h5 = dir / "run.h5";
  phasmid::testing::write_cruse_fixture(h5.string());
  Result r = run(q(PHASMID_BINARY) + " report " + q(h5.string()) + " 2>&1");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(fs::exists(dir / "run.html"));
  EXPECT_EQ(r.out, (dir / "run.html").string() + "\n");  // prints where the report is
  std::string html = slurp(dir / "run.html");
  EXPECT_NE(html.find("Chart.js v4"), std::string::npos);  // library inlined, not linked
  EXPECT_EQ(html.find("<script src"), std::string::npos);
  EXPECT_EQ(html.find("<link "), std::string::npos);
  for (const auto& e : fs::directory_iterator(dir))  // atomic write leaves no temporary behind
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();

  Result missing = run(q(PHASMID_BINARY) + " report " + q((dir / "missing.h5").string()) + " 2>&1");
  EXPECT_NE(missing.code, 0);
  EXPECT_NE(missing.out.find("no such file"), std::string::npos) << missing.out;
  EXPECT_EQ(std::count(missing.out.begin(), missing.out.end(), '\n'), 1) << missing.out;

  Result same = run(q(PHASMID_BINARY) + " report " + q(h5.string()) + " -o " + q(h5.string()) + " 2>&1");
  EXPECT_NE(same.code, 0);
  EXPECT_NE(same.out.find("is the input " + h5.string()), std::string::npos) << same.out;
  EXPECT_NO_THROW(extract(h5.string()));  // still the HDF5 file

  fs::path bad = dir / "bad.h5";
  std::ofstream(bad) << "garbage";
  Result noth5 = run(q(PHASMID_BINARY) + " report " + q(bad.string()) + " 2>&1");
  EXPECT_NE(noth5.code, 0);
  EXPECT_NE(noth5.out.find("not an HDF5 file"), std::string::npos) << noth5.out;
  EXPECT_FALSE(fs::exists(dir / "bad.html"));
}

// ------------------------------------------------------------------ rendering in Chromium

TEST(ReportRender, Trajectory) {
  fs::path h5 = work_dir() / "trajectory.h5";
  phasmid::testing::write_trajectory_fixture(h5.string());
  expect_renders("trajectory", h5,
                 {"fig-angles-front", "fig-angles-middle", "fig-angles-hind", "fig-angvel-middle", "fig-voltage-middle.thc",
                  "fig-voltage-middle.ctr", "fig-voltage-middle.fti", "fig-voltage-other-middle.fti", "fig-footfall",
                  "table-features",
                  "table-parameters"});
}

TEST(ReportRender, Cruse) {
  fs::path h5 = work_dir() / "cruse.h5";
  phasmid::testing::write_cruse_fixture(h5.string());
  expect_renders("cruse", h5, {"fig-position", "fig-protraction", "table-features", "list-ignored"});
}

TEST(ReportUnits, ExtractSweepRanges) {
  fs::path h5 = work_dir() / "unit_range_sweep.h5";
  phasmid::testing::write_range_sweep_fixture(h5.string());
  auto j = extract(h5.string());
  const auto& s = j["sweep"];
  EXPECT_EQ(s["design"], "one_at_a_time");
  ASSERT_TRUE(s.contains("ranges"));
  EXPECT_EQ(s["ranges"]["feature"], "table1_stable");
  const auto& p = s["ranges"]["parameters"];
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0]["name"], "T1");
  EXPECT_EQ(p[0]["units"], "unit");
  EXPECT_EQ(p[0]["lower"], 4.0);
  EXPECT_EQ(p[0]["upper"], 7.0);
  EXPECT_TRUE(p[0]["contiguous"].get<bool>());
  EXPECT_EQ(p[0]["in_range"], nlohmann::json({0, 0, 1, 1, 1, 1, 0}));
  EXPECT_EQ(p[1]["lower"], 1.0);
  EXPECT_EQ(p[1]["upper"], 4.0);
  EXPECT_FALSE(p[1]["contiguous"].get<bool>());
  for (auto& g : j["ignored"]) EXPECT_EQ(g.get<std::string>().find("/sweep"), std::string::npos) << g;
}

TEST(ReportRender, RangeSweep) {
  fs::path h5 = work_dir() / "range_sweep.h5";
  phasmid::testing::write_range_sweep_fixture(h5.string());
  // One panel per parameter and the table; no feature panels over a two-parameter plane.
  expect_renders("range_sweep", h5, {"fig-range-T1", "fig-range-T2", "table-sweep-ranges", "table-sweep-gaits"},
                 {"fig-sweep-table1_stable", "fig-sweep-gait"});
}

TEST(ReportRender, Sensitivity) {
  fs::path h5 = work_dir() / "sensitivity.h5";
  phasmid::testing::write_sensitivity_fixture(h5.string());
  expect_renders("sensitivity", h5,
                 {"fig-sens-period_ms", "fig-sens-stance_duration_ms", "fig-sens-swing_duration_ms",
                  "fig-sens-middle.fti.max_deg", "fig-sens-heatmap", "fig-floquet", "table-floquet", "fig-prc"});
}

TEST(ReportRender, Fit) {
  fs::path h5 = work_dir() / "fit.h5";
  phasmid::testing::write_fit_fixture(h5.string());
  expect_renders("fit", h5,
                 {"fig-fit-waterfall", "fig-fit-cost", "fig-fit-data-middle.fti", "table-fit-estimates",
                  "fig-fit-rse", "fig-fit-correlation"});
}

TEST(ReportRender, Sweep) {
  fs::path h5 = work_dir() / "sweep.h5";
  phasmid::testing::write_sweep_fixture(h5.string());
  // Two panels (start.tripod = 0 and 1) per figure; the second gets the suffix "--1".
  expect_renders("sweep", h5,
                 {"fig-sweep-period_ms", "fig-sweep-period_ms--1", "fig-sweep-stance_swing_ratio",
                  "fig-sweep-gait", "fig-sweep-gait--1", "table-sweep-gaits", "table-sweep-failures"});
}

TEST(ReportUnits, ExtractSweepOptions) {
  fs::path h5 = work_dir() / "unit_sweep_options.h5";
  phasmid::testing::write_sweep_fixture(h5.string(), phasmid::testing::SweepShape::LinkedRowsWithOptions);
  auto j = extract(h5.string());
  const auto& o = j["sweep"]["options"];
  ASSERT_EQ(o.size(), 2u);
  EXPECT_EQ(o[0]["name"], "gait");
  EXPECT_EQ(o[1]["values"][4], "source_contact");
  EXPECT_EQ(o[1]["values"].size(), 16u);
  for (auto& p : j["ignored"]) EXPECT_EQ(p.get<std::string>().find("/sweep/option"), std::string::npos) << p;
}

TEST(ReportRender, SweepOptionsArePanelsNotOverlays) {
  fs::path h5 = work_dir() / "sweep_options.h5";
  phasmid::testing::write_sweep_fixture(h5.string(), phasmid::testing::SweepShape::LinkedRowsWithOptions);
  // One panel per (gait, coupling_gate): 4; the linked third parameter adds none.
  expect_renders("sweep_options", h5,
                 {"fig-sweep-period_ms", "fig-sweep-period_ms--1", "fig-sweep-period_ms--2", "fig-sweep-period_ms--3",
                  "fig-sweep-gait--3", "table-sweep-gaits", "table-sweep-failures"},
                 {"fig-sweep-period_ms--4"});
}

TEST(ReportRender, SweepScatteredPoints) {
  fs::path h5 = work_dir() / "sweep_scatter.h5";
  phasmid::testing::write_sweep_fixture(h5.string(), phasmid::testing::SweepShape::Scattered);
  expect_renders("sweep_scatter", h5, {"fig-sweep-period_ms", "fig-sweep-gait", "table-sweep-failures"});
}

TEST(ReportRender, SweepOneParameter) {
  fs::path h5 = work_dir() / "sweep_1d.h5";
  phasmid::testing::write_sweep_fixture(h5.string(), phasmid::testing::SweepShape::OneParameter);
  expect_renders("sweep_1d", h5,
                 {"fig-sweep-period_ms", "fig-sweep-stance_swing_ratio", "fig-sweep-gait", "table-sweep-failures"});
}

TEST(ReportRender, MalformedGroupsAreListedNotFatal) {
  fs::path h5 = work_dir() / "malformed.h5";
  phasmid::testing::write_malformed_fixture(h5.string());
  auto j = extract(h5.string());
  std::set<std::string> ignored;
  for (auto& p : j["ignored"]) ignored.insert(p.get<std::string>());
  for (const char* p : {"/trajectory/angles/middle/ctr", "/trajectory/angles/hind", "/trajectory/footfall/middle",
                        "/features/matrix", "/sensitivity/features/period_ms", "/lonely_scalar",
                        "/fit/correlation (not n x n for the n parameter_names)",
                        "/sweep/gait_class (not one per point)"})
    EXPECT_TRUE(ignored.count(p)) << p;
  expect_renders("malformed", h5,
                 {"fig-angles-middle", "fig-voltage-x", "fig-sens-period_ms", "fig-sens-heatmap", "fig-fit-cost",
                  "table-fit-estimates", "list-ignored"},
                 {}, /*screenshot=*/false);
}

TEST(ReportRender, FileWithNothingToDraw) {
  fs::path h5 = work_dir() / "empty.h5";
  phasmid::testing::write_empty_fixture(h5.string());
  ASSERT_FALSE(chromium().empty()) << "chromium is required";
  Page p = load(make_report(h5));
  EXPECT_EQ(p.attr("data-status"), "ok") << p.attr("data-errors");
  EXPECT_EQ(p.attr("data-figures"), "");
  EXPECT_NE(p.dom.find("none of the groups a report can show"), std::string::npos);
}

TEST(ReportRender, DetectsScriptErrors) {
  // The checks above must be able to fail: a page whose script throws is reported as such.
  ASSERT_FALSE(chromium().empty()) << "chromium is required";
  fs::path h5 = work_dir() / "broken.h5";
  phasmid::testing::write_cruse_fixture(h5.string());
  fs::path html = make_report(h5);
  std::string page = slurp(html);
  auto pos = page.find("header();");
  ASSERT_NE(pos, std::string::npos);
  page.replace(pos, 9, "header(); null.boom();");
  std::ofstream(html, std::ios::binary | std::ios::trunc) << page;
  Page p = load(html);
  EXPECT_EQ(p.attr("data-status"), "error");
  EXPECT_FALSE(p.console_errors().empty()) << p.log;
}

// ------------------------------------------------------------------ global sensitivity analysis
namespace {
// A small `phasmid gsa` run of the registered Ishigami kind (Sobol' N = 64, or Morris r = 16).
fs::path gsa_file(const std::string& method) {
  fs::path cfg = work_dir() / ("gsa_" + method + ".toml"), h5 = work_dir() / ("gsa_" + method + ".h5");
  std::ofstream c(cfg);
  c << "[model]\ntype = \"ishigami\"\n";
  for (const char* x : {"x1", "x2", "x3"}) c << "[[sweep.parameter]]\nname = \"" << x << "\"\nlower = -3.14159\nupper = 3.14159\n";
  c << "[gsa]\nmethod = \"" << method << "\"\nfeatures = [\"y\"]\nbootstrap = 100\n"
    << (method == "sobol" ? "N = 64\n" : "trajectories = 16\nlevels = 4\n");
  c.close();
  Result r = run(q(PHASMID_BINARY) + " gsa " + q(cfg.string()) + " -q -o " + q(h5.string()) + " 2>&1");
  EXPECT_EQ(r.code, 0) << r.out;
  return h5;
}
}  // namespace

TEST(ReportUnits, ExtractGsaReadsTheStoredIndices) {
  const fs::path h5 = gsa_file("sobol");
  const auto j = phasmid::report::extract(h5.string());
  const auto stored = phasmid::gsa::read_gsa_h5(phasmid::io::H5Reader(h5.string()));
  const auto& g = j.at("gsa");
  EXPECT_EQ(g.at("method"), "sobol");
  EXPECT_EQ(g.at("N"), 64);
  EXPECT_EQ(g.at("rows"), 64 * 8);
  const auto& y = g.at("features").at(0);
  EXPECT_EQ(y.at("name"), "y");
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(y.at("ST").at(k).get<double>(), stored.features[0].sobol.ST[k]);
    EXPECT_EQ(y.at("S1_conf").at(k).get<double>(), stored.features[0].sobol.S1_conf[k]);
  }
  EXPECT_EQ(y.at("convergence").at("n"), (std::vector<int>{8, 16, 32, 64}));
  EXPECT_EQ(y.at("counts").at("n_used"), 64);
  // Which indices the report greys: the analysis' own rule, and at N = 64 some of them.
  const auto res = phasmid::gsa::resolve(stored, stored.features[0]);
  std::size_t unresolved = 0;
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(y.at("resolved").at("S1").at(k).get<bool>(), res.S1[k] != 0);
    EXPECT_EQ(y.at("resolved").at("ST").at(k).get<bool>(), res.ST[k] != 0);
    unresolved += !res.S1[k] + !res.ST[k];
  }
  EXPECT_GT(unresolved, 0u);
  EXPECT_EQ(y.at("resolved").at("n_unresolved"), unresolved);
  EXPECT_EQ(y.at("resolved").at("n_to_resolve").get<double>(), res.n_to_resolve);
  EXPECT_EQ(g.at("resolution"), 0.1);
}

TEST(ReportRender, GsaSobol) {
  expect_renders("gsa_sobol", gsa_file("sobol"), {"table-gsa-counts", "table-gsa-resolution", "fig-gsa-heatmap", "fig-gsa-y", "fig-gsa-conv-y"},
                 {"fig-gsa-plane-y"});
}

TEST(ReportRender, GsaMorris) {
  expect_renders("gsa_morris", gsa_file("morris"), {"table-gsa-counts", "table-gsa-resolution", "fig-gsa-y", "fig-gsa-plane-y", "fig-gsa-conv-y"},
                 {"fig-gsa-heatmap"});
}
