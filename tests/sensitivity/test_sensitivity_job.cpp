// The [sensitivity] config section and the complete sensitivity file (what the verb writes).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>

#include "common/error.hpp"
#include "model/mechanical_joint_model.hpp"
#include "continuation/sensitivity_job.hpp"
#include "config/sensitivity_section.hpp"

using namespace phasmid;

TEST(SensitivityJob, ParsesSectionRunsAndWritesFile) {
  model::MechanicalJointModel m("middle", model::JointType::Fti, true, 250, 500, 45);
  auto tbl = toml::parse(R"(
[sensitivity]
parameters = ["middle.fti.k_E.flexion", "middle.fti.k_F.flexion", "middle.fti.b_v", "middle.fti.switch.period_ms"]
t_end_ms = 2500
output_dt_ms = 5
discard_ms = 500
method = "forward"
trajectory = false
floquet = true
transient_ms = 1500
max_period_ms = 600
tolerance_factor = 10
)");
  auto job = config::parse_sensitivity_section(*tbl["sensitivity"].as_table(), m, "test.toml");
  EXPECT_EQ(job.options.parameters.size(), 4u);
  EXPECT_DOUBLE_EQ(job.options.t_end_ms, 2500);
  EXPECT_FALSE(job.options.write_trajectory);
  EXPECT_TRUE(job.floquet);
  EXPECT_DOUBLE_EQ(job.options.solver.sensitivity_tolerance_factor, 10.0);
  auto p = m.parameters().values();
  auto out = sensitivity::run_sensitivity_job(m, p, job);
  ASSERT_TRUE(out.has_floquet);
  EXPECT_NEAR(out.floquet.orbit.period_ms, 500.0, 1e-4);
  EXPECT_NE(sensitivity::format_summary(out).find("period_ms"), std::string::npos);
  const std::string file = "/tmp/phasmid_sensjob_" + std::to_string(::getpid()) + ".h5";
  sensitivity::write_sensitivity_file(file, m, p, job, out, {"[sensitivity]\n", "phasmid sensitivity test.toml"});
  io::H5Reader in(file);
  EXPECT_EQ(in.read_strings("/sensitivity/parameters"), job.options.parameters);
  EXPECT_EQ(in.read_strings("/sensitivity/parameter_method"),
            (std::vector<std::string>{"forward", "forward", "forward", "forward"}));
  EXPECT_NEAR(in.read_doubles("/features/period_ms")[0], 500.0, 1e-4);
  EXPECT_EQ(in.read_string_attribute("/features/period_ms", "units"), "ms");
  // d period / d switch.period_ms = 1 (the cycle follows the forcing).
  EXPECT_NEAR(in.read_doubles("/sensitivity/features/period_ms")[3], 1.0, 1e-4);
  EXPECT_FALSE(in.exists("/sensitivity/trajectory"));
  EXPECT_DOUBLE_EQ(in.read_double_attribute("/sensitivity", "tolerance_factor"), 10.0);
  EXPECT_EQ(in.read_doubles("/sensitivity/floquet/multipliers_abs").size(), 2u);
  EXPECT_EQ(in.read_doubles("/parameters/values").size(), p.size());
  std::remove(file.c_str());
}

TEST(SensitivityJob, ErrorsNameFileLineAndKey) {
  model::MechanicalJointModel m("middle", model::JointType::Fti, true, 250, 500, 45);
  auto expect_error = [&](const char* text, const std::string& needle) {
    auto tbl = toml::parse(text);
    try {
      config::parse_sensitivity_section(*tbl["sensitivity"].as_table(), m, "cfg.toml");
      ADD_FAILURE() << "no error for " << text;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expect_error("[sensitivity]\nparameters = [\"middle.fti.k_Q\"]\n", "cfg.toml:2");
  expect_error("[sensitivity]\nparameters = [\"middle.fti.k_Q\"]\n", "middle.fti.k_Q");
  expect_error("[sensitivity]\n\nspeed = 3\n", "unknown key 'speed'");
  expect_error("[sensitivity]\nmethod = \"adjoint\"\n", "adjoint");
  expect_error("[sensitivity]\nt_end_ms = \"long\"\n", "t_end_ms must be a finite number");
  expect_error("[sensitivity]\n\ntolerance_factor = 0\n", "cfg.toml:3");
  expect_error("[sensitivity]\ntolerance_factor = -1\n", "tolerance_factor must be a positive number");
}
