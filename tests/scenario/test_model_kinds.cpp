// Model kinds through the generic verbs' code paths: a kind registered from the test tree runs
// through simulate, sweep and fit exactly as the shipped kinds do (docs/architecture.md), and
// the registry refuses unknown kinds and keys with one line naming file:line.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "common/error.hpp"
#include "config/config.hpp"
#include "config/sweep_inputs.hpp"
#include "config/fit_section.hpp"
#include "fit/fit_run.hpp"
#include "io/h5_file.hpp"
#include "scenario/registry.hpp"
#include "sweep/sweep_runner.hpp"
#include "toy_kind.hpp"

using namespace phasmid;
namespace fs = std::filesystem;

namespace {

const char* kToy = R"([model]
type = "toy_vdp"
[simulation]
t_end_ms = 120
discard_ms = 60
rtol = 1e-10
atol = 1e-10
)";

double feature(const std::vector<features::Feature>& fs, const std::string& name) {
  auto it = std::find_if(fs.begin(), fs.end(), [&](const auto& f) { return f.name == name; });
  if (it == fs.end()) throw Error("no feature " + name);
  return it->value;
}

std::string error_of(const std::string& text) {
  try {
    config::build_scenario(config::parse_config(text, "k.toml"));
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(ModelKinds, ToyKindSimulatesWithTheKnownPeriodAndWritesItsFeatures) {
  const config::Config cfg = config::parse_config(kToy, "toy.toml");
  auto s = config::build_scenario(cfg, {"toy.mu=2"});
  EXPECT_EQ(s->kind(), "toy_vdp");
  auto run = s->run(s->parameters().values(), config::simulation_settings(cfg, s.get()));
  EXPECT_NEAR(feature(run->features(), "period_ms"), 7.6299, 1e-3);
  // the feature catalogue lists what the run computed, with the same units
  const auto catalogue = s->feature_catalogue();
  for (const auto& f : run->features()) {
    auto it = std::find_if(catalogue.begin(), catalogue.end(), [&](const auto& c) { return c.name == f.name; });
    ASSERT_NE(it, catalogue.end()) << f.name;
    EXPECT_EQ(it->unit, f.unit) << f.name;
  }
  const fs::path out = fs::temp_directory_path() / ("toy_" + std::to_string(getpid()) + ".h5");
  {
    io::H5Writer w(out.string());
    run->write(w);
    w.commit();
  }
  io::H5Reader r(out.string());
  EXPECT_NEAR(feature(features::read_features_h5(r), "period_ms"), 7.6299, 1e-3);
  EXPECT_EQ(r.read_strings("/parameters/names"), (std::vector<std::string>{"toy.mu", "toy.x0"}));
  fs::remove(out);
}

TEST(ModelKinds, ToyKindSweepsOverMuWithTheKnownPeriods) {
  const config::Config cfg = config::parse_config(std::string(kToy) + R"([sweep]
[[sweep.parameter]]
name = "toy.mu"
values = [1.0, 2.0, 5.0]
)",
                                                  "toy_sweep.toml");
  const fs::path out = fs::temp_directory_path() / ("toy_sweep_" + std::to_string(getpid()) + ".h5");
  sweep::SweepOptions o;
  o.output = out.string();
  o.progress = false;
  o.threads = 2;
  ASSERT_TRUE(sweep::run_sweep(config::sweep_inputs(cfg, {}), o).complete);
  io::H5Reader r(out.string());
  const auto period = r.read_doubles("/sweep/features/period_ms");
  ASSERT_EQ(period.size(), 3u);
  EXPECT_NEAR(period[0], 6.6633, 1e-3);
  EXPECT_NEAR(period[1], 7.6299, 1e-3);
  EXPECT_NEAR(period[2], 11.6125, 1e-3);
  fs::remove(out);
}

TEST(ModelKinds, ToyKindFitRecoversMuFromThePeriod) {
  const config::Config cfg = config::parse_config(std::string(kToy) + R"([fit]
[fit.parameters]
"toy.mu" = { lower = 0.5, upper = 4.0, nominal = 1.0 }
[[fit.feature]]
name = "period_ms"
value = 7.62987
tolerance = 0.001
)",
                                                  "toy_fit.toml");
  auto s = config::build_scenario(cfg);
  fit::FitSpec spec = config::fit_spec(cfg, *s, {});
  auto problem = s->make_fit(spec);
  spec.optimizer.progress = false;
  const fit::FitResult result = fit::run_fit(*problem, spec);
  ASSERT_TRUE(result.best().converged) << result.best().termination;
  EXPECT_NEAR(result.estimate.at(0), 2.0, 2e-3);
}

TEST(ModelKinds, UnknownKindAndKeysNameTheLineAndTheNearestName) {
  EXPECT_NE(error_of("[model]\ntype = \"toy_vpd\"\n").find("k.toml:2: unknown model type 'toy_vpd' (did you mean 'toy_vdp'?)"),
            std::string::npos)
      << error_of("[model]\ntype = \"toy_vpd\"\n");
  const std::string msg = error_of("[model]\ntype = \"single_joint\"\njiont = \"fti\"\n");
  EXPECT_NE(msg.find("k.toml:3: unknown key 'jiont' in [model] (did you mean 'joint'?)"), std::string::npos) << msg;
  EXPECT_NE(error_of("[model]\nleg = \"middle\"\n").find("k.toml:1: [model] needs type"), std::string::npos);
}

// A list in [model] (cruse1980's stability_periods_ms) read through the ModelSection the
// config layer implements: each bad value is blamed on its own element's line.
TEST(ModelKinds, ListKeysNameTheLineOfTheBadElement) {
  const std::string head = "[model]\ntype = \"cruse1980\"\n";
  std::string msg = error_of(head + "stability_periods_ms = 500\n");
  EXPECT_NE(msg.find("k.toml:3: stability_periods_ms must be a list of periods (ms)"), std::string::npos) << msg;
  msg = error_of(head + "stability_periods_ms = [\n  500,\n  -5,\n]\n");
  EXPECT_NE(msg.find("k.toml:5: stability_periods_ms: a period must be > 0 ms"), std::string::npos) << msg;
  msg = error_of(head + "stability_periods_ms = [500, \"x\"]\n");
  EXPECT_NE(msg.find("k.toml:3:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("stability_periods_ms"), std::string::npos) << msg;
  EXPECT_EQ(error_of(head + "stability_periods_ms = [500, 700]\n"), "no error");
}

// The analytic test problems are registered as such; every other built-in kind is a model.
TEST(ModelKinds, TestProblemsAreRegisteredApartFromTheModels) {
  const std::set<std::string> tests = {"ishigami", "sobol_g", "stuart_landau", "van_der_pol", "relay_oscillator"};
  for (const auto& k : scenario::model_kinds())
    EXPECT_EQ(k.category == scenario::KindCategory::TestProblem, tests.count(k.name) == 1) << k.name;
}

TEST(ModelKinds, EveryBuiltInKindIsRegisteredOnce) {
  std::vector<std::string> names;
  for (const auto& k : scenario::model_kinds()) names.push_back(k.name);
  for (const char* n : {"mechanical_joint", "coupled_ctr_fti", "single_joint", "leg", "three_legs", "curve_walking",
                        "cruse1980", "ishigami", "sobol_g", "stuart_landau", "van_der_pol",
                        "relay_oscillator", "toy_vdp"})
    EXPECT_EQ(std::count(names.begin(), names.end(), n), 1) << n;
}
