// /gsa layout: what write_gsa_h5 stores is what read_gsa_h5 returns, with units everywhere.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "common/error.hpp"
#include "gsa/gsa_h5.hpp"
#include "gsa_test_functions.hpp"

using namespace phasmid;
using namespace phasmid::gsa;

namespace {

std::string temp(const char* name) {
  auto p = (std::filesystem::temp_directory_path() / name).string();
  std::filesystem::remove(p);
  return p;
}

GsaResult ishigami_result(const std::string& method) {
  GsaResult r;
  r.method = method;
  r.parameters = gsa_test::Ishigami::parameters();
  r.parameters[2].unit = "mV";
  r.bootstrap.resamples = 50;
  r.bootstrap.seed = 12345678901234567ull;
  FeatureResult f;
  f.name = "period_ms";
  f.unit = "ms";
  if (method == "sobol") {
    r.saltelli_options.n_base = 64;
    r.saltelli_options.seed = 42;
    r.saltelli = saltelli_sample(3, r.saltelli_options);
  } else {
    r.morris_options.trajectories = 6;
    r.morris_options.pool = 12;
    r.morris = morris_sample(3, r.morris_options);
  }
  f.y = gsa_test::evaluate("ishigami", scale_to_parameters(r.unit_design(), r.parameters), 3);
  f.y[5] = std::numeric_limits<double>::quiet_NaN();
  if (method == "sobol") f.sobol = sobol_analyze(3, true, f.y, r.bootstrap);
  else f.morris = morris_analyze(r.morris, f.y, r.bootstrap);
  r.features.push_back(f);
  return r;
}

// Writes `r` to a fresh temporary file and returns its path.
std::string written(const GsaResult& r, const std::string& name) {
  const std::string path = temp(name.c_str());
  io::H5Writer w(path);
  write_gsa_h5(w, r);
  w.commit();
  return path;
}

void expect_same_values(const std::vector<double>& a, const std::vector<double>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::isnan(a[i])) EXPECT_TRUE(std::isnan(b[i])) << i;
    else EXPECT_EQ(a[i], b[i]) << i;
}

// What both methods store alike: method, parameters, design, bootstrap settings, outputs.
void expect_same_run(const GsaResult& r, const GsaResult& back) {
  EXPECT_EQ(back.method, r.method);
  EXPECT_EQ(back.bootstrap.seed, 12345678901234567ull);
  EXPECT_EQ(back.bootstrap.resamples, r.bootstrap.resamples);
  EXPECT_EQ(back.parameters[2].unit, "mV");
  expect_same_values(back.unit_design(), r.unit_design());
  ASSERT_EQ(back.features.size(), 1u);
  EXPECT_EQ(back.features[0].unit, "ms");
  expect_same_values(back.features[0].y, r.features[0].y);
}

// An Ishigami result of `method`, written, reopened and read back; checks what both methods
// store alike.
struct RoundTrip {
  GsaResult r;
  std::string path;
  io::H5Reader h;
  GsaResult back;
  explicit RoundTrip(const std::string& method)
      : r(ishigami_result(method)), path(written(r, "phasmid_gsa_" + method + ".h5")), h(path), back(read_gsa_h5(h)) {
    expect_same_run(r, back);
  }
};

}  // namespace

TEST(GsaH5, SobolRoundTrip) {
  const RoundTrip rt("sobol");
  const GsaResult &r = rt.r, &back = rt.back;
  const io::H5Reader& h = rt.h;
  EXPECT_EQ(back.saltelli_options.n_base, 64u);
  EXPECT_EQ(back.saltelli_options.seed, 42u);
  EXPECT_TRUE(back.saltelli.second_order);
  const FeatureResult& f = back.features[0];
  expect_same_values(f.sobol.S1, r.features[0].sobol.S1);
  expect_same_values(f.sobol.ST_conf, r.features[0].sobol.ST_conf);
  expect_same_values(f.sobol.S2, r.features[0].sobol.S2);
  EXPECT_EQ(f.sobol.counts.n_dropped, 1u);
  EXPECT_EQ(f.sobol.counts.n_used, 63u);
  EXPECT_EQ(h.dims("/gsa/period_ms/S2"), (std::vector<hsize_t>{3, 3}));
  EXPECT_EQ(h.dims("/gsa/design/values"), (std::vector<hsize_t>{64 * 8, 3}));
  EXPECT_EQ(h.read_string_attribute("/gsa", "estimator_ST"), "Jansen 1999");
  for (const char* ds : {"Y", "S1", "S1_conf", "ST", "ST_conf", "S2", "S2_conf"})
    EXPECT_FALSE(h.read_string_attribute(std::string("/gsa/period_ms/") + ds, "units").empty()) << ds;
  EXPECT_EQ(h.read_string_attribute("/gsa/design/values", "units"), "1, 1, mV");
}

TEST(GsaH5, MorrisRoundTrip) {
  const RoundTrip rt("morris");
  const GsaResult &r = rt.r, &back = rt.back;
  const io::H5Reader& h = rt.h;
  EXPECT_EQ(back.morris.levels, 4);
  EXPECT_EQ(back.morris_options.pool, 12u);
  EXPECT_DOUBLE_EQ(back.morris.delta, 2.0 / 3.0);
  const FeatureResult& f = back.features[0];
  expect_same_values(f.morris.mu_star, r.features[0].morris.mu_star);
  expect_same_values(f.morris.sigma, r.features[0].morris.sigma);
  EXPECT_EQ(h.read_string_attribute("/gsa/period_ms/mu_star", "units"), "ms");
  EXPECT_EQ(f.morris.counts.n_dropped, 1u);
  // The design read back analyses to the same indices.
  const MorrisIndices again = morris_analyze(back.morris, f.y, back.bootstrap);
  expect_same_values(again.mu_star_conf, r.features[0].morris.mu_star_conf);
}

TEST(GsaH5, RejectsReservedFeatureName) {
  const std::string path = temp("phasmid_gsa_bad.h5");
  GsaResult r = ishigami_result("sobol");
  r.features[0].name = "design";
  io::H5Writer w(path);
  EXPECT_THROW(write_gsa_h5(w, r), Error);
}
