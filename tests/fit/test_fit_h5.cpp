// The HDF5 layout of a fit result (docs/fit.md): /fit/..., multistart waterfall, profiles,
// data vs model, best-fit trajectory, parameters, root attributes.
#include <gtest/gtest.h>

#include <filesystem>

#include "config/fit_section.hpp"
#include "fit/fit_run.hpp"
#include "fit_test_util.hpp"
#include "io/h5_file.hpp"

using namespace phasmid;

TEST(FitH5, WritesTheDocumentedGroups) {
  auto cfg = config::load_config(fittest::source("configs/fit_fti_kinematic_synthetic.toml"));
  auto m = config::build_model(cfg);
  fit::FitOverrides ov;
  ov.multistart = 3;
  fit::FitSpec spec = fit::load_fit_spec(cfg, *m, ov);
  spec.profile = {"middle.fti.b_v"};
  spec.profile_points = 5;
  fit::FitProblem p(*m, spec.parameters, spec.targets, spec.problem);
  fit::FitResult r = fit::run_fit(p, spec);
  ASSERT_TRUE(r.best().converged);
  const std::string path = (std::filesystem::temp_directory_path() / "phasmid_test_fit.h5").string();
  {
    io::H5Writer w(path);
    w.write_run_info({cfg.text, "test"});
    fit::write_fit_h5(w, p, spec, r);
    w.commit();
  }
  io::H5Reader in(path);
  const size_t n = 5;
  EXPECT_EQ(in.read_strings("/fit/parameter_names").size(), n);
  EXPECT_EQ(in.read_doubles("/fit/estimate").size(), n);
  EXPECT_EQ(in.read_doubles("/fit/standard_error").size(), n);
  EXPECT_GE(in.read_doubles("/fit/cost_history").size(), 2u);
  EXPECT_EQ(in.dims("/fit/correlation"), (std::vector<hsize_t>{n, n}));
  auto corr = in.read_doubles("/fit/correlation");
  for (size_t j = 0; j < n; ++j) EXPECT_NEAR(corr[j * n + j], 1.0, 1e-12);
  EXPECT_EQ(in.read_doubles("/fit/multistart/final_cost").size(), 3u);
  EXPECT_EQ(in.dims("/fit/multistart/start_points"), (std::vector<hsize_t>{3, n}));
  EXPECT_EQ(in.read_doubles("/fit/residuals").size(), p.num_residuals());
  EXPECT_EQ(in.read_doubles("/fit/profile/middle.fti.b_v/delta_chi2").size(), 5u);
  auto t = in.read_doubles("/fit/data/time");
  EXPECT_EQ(t.size(), 201u);
  EXPECT_EQ(in.read_doubles("/fit/model/middle.fti").size(), t.size());
  EXPECT_EQ(in.read_doubles("/fit/data/middle.fti").size(), t.size());
  EXPECT_TRUE(in.exists("/trajectory/time"));
  EXPECT_TRUE(in.exists("/trajectory/angles/middle/fti"));
  EXPECT_EQ(in.read_strings("/parameters/names").size(), m->parameters().size());
  EXPECT_EQ(in.read_string_attribute("/fit/estimate", "units"), "see /fit/parameter_units");
  EXPECT_FALSE(in.read_string_attribute("/", "phasmid_version").empty());
  std::filesystem::remove(path);
}
