// Feature and trajectory sensitivities (forward, event-time formula) against central finite
// differences on the Section 3.1 mechanical joints (FTi, CTr, ThC), across the prescribed
// switches of the spring constants.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <unistd.h>

#include "common/error.hpp"
#include "io/h5_file.hpp"
#include "model/mechanical_joint_model.hpp"
#include "sensitivity/sensitivity.hpp"

using namespace phasmid;

namespace {

struct Case {
  const char* name;
  model::JointType joint;
  double first_phase_ms, angle0_deg;
};

std::vector<std::string> mechanical_parameters(const model::OdeModel& m) {
  // Every parameter the equations read: geometry, inertia, viscosity, phase-wise spring
  // constants (not the targets gamma_min/max, not the switch timing or initial angle).
  std::vector<std::string> out;
  for (auto& p : m.parameters().all()) {
    const std::string tail = p.name.substr(p.name.rfind('.') + 1);
    bool skip = p.name.find(".switch.") != std::string::npos;
    for (const char* a : {"alpha", "beta", "gamma"})
      for (const char* suffix : {"_min", "_max", "0"}) skip = skip || tail == std::string(a) + suffix;
    if (!skip) out.push_back(p.name);
  }
  return out;
}

sensitivity::SensitivityOptions options_for(const model::OdeModel& m, sensitivity::Method method) {
  sensitivity::SensitivityOptions o;
  o.parameters = mechanical_parameters(m);
  o.t_end_ms = 2000;
  o.output_dt_ms = 10;
  o.discard_ms = 500;
  o.method = method;
  o.solver.rtol = 1e-10;
  o.solver.atol = 1e-10;
  return o;
}

// Compares every feature x parameter: 1% where the finite difference is well conditioned
// (|relative sensitivity| >= 1e-3); otherwise the relative sensitivities agree to 1e-5.
void expect_features_agree(const sensitivity::SensitivityReport& fwd, const sensitivity::SensitivityReport& fd,
                           const std::string& label) {
  ASSERT_EQ(fwd.features.size(), fd.features.size());
  ASSERT_GT(fwd.features.size(), 6u);
  int well = 0;
  double worst = 0;
  for (size_t f = 0; f < fwd.features.size(); ++f) {
    ASSERT_EQ(fwd.features[f].name, fd.features[f].name);
    for (size_t j = 0; j < fwd.parameters.size(); ++j) {
      const double a = fwd.absolute(f, j), b = fd.absolute(f, j);
      const double rb = fd.relative(f, j), ra = fwd.relative(f, j);
      ASSERT_TRUE(std::isfinite(a) && std::isfinite(b)) << label << " " << fwd.features[f].name;
      if (std::abs(rb) >= 1e-3) {
        EXPECT_NEAR(a, b, 0.01 * std::abs(b)) << label << ": d " << fwd.features[f].name << " / d "
                                              << fwd.parameters[j];
        ++well;
        worst = std::max(worst, std::abs(a - b) / std::abs(b));
      } else {
        EXPECT_NEAR(ra, rb, 1e-5) << label << ": d " << fwd.features[f].name << " / d " << fwd.parameters[j];
      }
    }
  }
  std::printf("%s: %d well-conditioned feature sensitivities, worst relative difference %.2e\n", label.c_str(),
              well, worst);
  EXPECT_GT(well, 20) << label;
}

class MechanicalSensitivity : public ::testing::TestWithParam<Case> {};

}  // namespace

TEST_P(MechanicalSensitivity, FeatureSensitivitiesMatchCentralDifferences) {
  const Case c = GetParam();
  model::MechanicalJointModel m("middle", c.joint, true, c.first_phase_ms, 500, c.angle0_deg);
  auto p = m.parameters().values();
  auto fwd = sensitivity::analyse_sensitivities(m, p, options_for(m, sensitivity::Method::Forward));
  auto fd = sensitivity::analyse_sensitivities(m, p, options_for(m, sensitivity::Method::FiniteDifference));
  for (auto& how : fwd.parameter_method) EXPECT_EQ(how, "forward");
  for (auto& how : fd.parameter_method) EXPECT_EQ(how, "fd");
  EXPECT_EQ(fd.fd_runs, 2 * static_cast<long>(fd.parameters.size()));
  expect_features_agree(fwd, fd, c.name);
}

TEST_P(MechanicalSensitivity, TrajectorySensitivitiesMatchCentralDifferencesAcrossSwitches) {
  const Case c = GetParam();
  model::MechanicalJointModel m("middle", c.joint, true, c.first_phase_ms, 500, c.angle0_deg);
  auto p = m.parameters().values();
  auto fwd = sensitivity::analyse_sensitivities(m, p, options_for(m, sensitivity::Method::Forward));
  auto fd = sensitivity::analyse_sensitivities(m, p, options_for(m, sensitivity::Method::FiniteDifference));
  ASSERT_EQ(fwd.trajectory.size(), fd.trajectory.size());
  const size_t nt = fwd.time.size(), n = fwd.state_names.size(), np = fwd.parameters.size();
  int compared = 0;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < np; ++j) {
      double scale = 0;
      for (size_t k = 0; k < nt; ++k) scale = std::max(scale, std::abs(fd.trajectory_sens(k, i, j)));
      if (scale == 0) continue;
      for (size_t k = 0; k < nt; k += 5) {  // every 50 ms: both sides of every switch
        const double a = fwd.trajectory_sens(k, i, j), b = fd.trajectory_sens(k, i, j);
        EXPECT_NEAR(a, b, 0.01 * std::abs(b) + 1e-4 * scale)
            << c.name << " t=" << fwd.time[k] << " d " << fwd.state_names[i] << " / d " << fwd.parameters[j];
        ++compared;
      }
    }
  std::printf("%s: %d trajectory sensitivities compared\n", c.name, compared);
  EXPECT_GT(compared, 200);
}

INSTANTIATE_TEST_SUITE_P(Joints, MechanicalSensitivity,
                         ::testing::Values(Case{"fti", model::JointType::Fti, 250, 45},
                                           Case{"ctr", model::JointType::Ctr, 188, 30},
                                           Case{"thc", model::JointType::Thc, 125, 70}),
                         [](const ::testing::TestParamInfo<Case>& i) { return std::string(i.param.name); });

TEST(Sensitivity, SwitchTimingSensitivitiesWithJumpConditionsMatchCentralDifferences) {
  // The prescribed switch times move with switch.period_ms and switch.first_phase_ms: the
  // forward method applies s+ = s- + (f- - f+) dtau/dp at every switch.
  model::MechanicalJointModel m("middle", model::JointType::Fti, true, 250, 500, 45);
  auto o = options_for(m, sensitivity::Method::Forward);
  o.parameters = {"middle.fti.b_v", "middle.fti.switch.period_ms", "middle.fti.switch.first_phase_ms",
                  "middle.fti.gamma0"};
  o.t_end_ms = 2000;
  o.output_dt_ms = 7;
  o.discard_ms = 500;
  auto p = m.parameters().values();
  auto fwd = sensitivity::analyse_sensitivities(m, p, o);
  EXPECT_EQ(fwd.parameter_method, (std::vector<std::string>{"forward", "forward", "forward", "forward"}));
  // After the transient the gait period equals the forcing period: d period / d period_ms = 1.
  size_t f = fwd.feature_index("period_ms");
  EXPECT_NEAR(fwd.absolute(f, 1), 1.0, 1e-6);
  EXPECT_NEAR(fwd.absolute(f, 2), 0.0, 1e-6);
  o.method = sensitivity::Method::FiniteDifference;
  auto fd = sensitivity::analyse_sensitivities(m, p, o);
  for (size_t g = 0; g < fwd.features.size(); ++g)
    for (size_t j = 0; j < fwd.parameters.size(); ++j) {
      if (std::abs(fd.relative(g, j)) >= 1e-3)
        EXPECT_NEAR(fwd.absolute(g, j), fd.absolute(g, j), 0.01 * std::abs(fd.absolute(g, j)))
            << "d " << fwd.features[g].name << " / d " << fwd.parameters[j];
      else
        EXPECT_NEAR(fwd.relative(g, j), fd.relative(g, j), 1e-5) << "d " << fwd.features[g].name << " / d " << fwd.parameters[j];
    }
  const size_t nt = fwd.time.size();
  int compared = 0;
  for (size_t i = 0; i < 2; ++i)
    for (size_t j = 0; j < fwd.parameters.size(); ++j) {
      double scale = 0;
      for (size_t k = 0; k < nt; ++k) scale = std::max(scale, std::abs(fd.trajectory_sens(k, i, j)));
      for (size_t k = 0; k < nt; ++k) {
        // At a switch time itself (multiples of 250 ms: 1750, 2000) y(t) has a kink as a
        // function of the switch parameters, so neither one-sided derivative equals the
        // central difference there; compare everywhere else.
        if (std::abs(std::remainder(fwd.time[k], 250.0)) < 1e-9) continue;
        const double a = fwd.trajectory_sens(k, i, j), b = fd.trajectory_sens(k, i, j);
        EXPECT_NEAR(a, b, 0.01 * std::abs(b) + 1e-4 * scale)
            << "t=" << fwd.time[k] << " d " << fwd.state_names[i] << " / d " << fwd.parameters[j];
        ++compared;
      }
    }
  EXPECT_GT(compared, 1000);
}

TEST(Sensitivity, InitialAngleSensitivityIsExactFromTheStart) {
  // gamma0 sets the initial state: forward sensitivities start from s(0) = dy0/dp.
  model::MechanicalJointModel m("middle", model::JointType::Fti, true, 250, 500, 45);
  auto o = options_for(m, sensitivity::Method::Forward);
  o.parameters = {"middle.fti.gamma0", "middle.fti.b_v"};
  o.t_end_ms = 1500;
  o.discard_ms = 0;
  auto p = m.parameters().values();
  auto fwd = sensitivity::analyse_sensitivities(m, p, o);
  EXPECT_EQ(fwd.parameter_method, (std::vector<std::string>{"forward", "forward"}));
  // d gamma(0) / d gamma0 = pi/180 rad/deg; dy0/dp comes from central differences of the
  // algebraic initial state (round-off ~1e-10 relative).
  EXPECT_NEAR(fwd.trajectory_sens(0, 0, 0), M_PI / 180, 1e-9 * M_PI / 180);
  o.method = sensitivity::Method::FiniteDifference;
  auto fd = sensitivity::analyse_sensitivities(m, p, o);
  const size_t nt = fwd.time.size();
  for (size_t i = 0; i < 2; ++i) {
    double scale = 0;
    for (size_t k = 0; k < nt; ++k) scale = std::max(scale, std::abs(fd.trajectory_sens(k, i, 0)));
    ASSERT_GT(scale, 0);
    for (size_t k = 0; k < nt; k += 5)
      EXPECT_NEAR(fwd.trajectory_sens(k, i, 0), fd.trajectory_sens(k, i, 0), 0.01 * std::abs(fd.trajectory_sens(k, i, 0)) + 1e-4 * scale)
          << "t=" << fwd.time[k] << " state " << i;
  }
  // The first maximum (134 ms) depends on the initial angle; the features average it in.
  size_t f = fwd.feature_index("middle.fti.angle_max_deg");
  EXPECT_GT(std::abs(fd.relative(f, 0)), 1e-4);
  EXPECT_NEAR(fwd.absolute(f, 0), fd.absolute(f, 0), 0.01 * std::abs(fd.absolute(f, 0)));
}

TEST(Sensitivity, RelativeSensitivitiesAndRankingAreConsistent) {
  model::MechanicalJointModel m("middle", model::JointType::Fti, true, 250, 500, 45);
  auto o = options_for(m, sensitivity::Method::Forward);
  auto p = m.parameters().values();
  auto r = sensitivity::analyse_sensitivities(m, p, o);
  for (size_t f = 0; f < r.features.size(); ++f) {
    for (size_t j = 0; j < r.parameters.size(); ++j)
      EXPECT_DOUBLE_EQ(r.relative(f, j), r.parameter_values[j] / r.features[f].value * r.absolute(f, j));
    ASSERT_EQ(r.ranking[f].size(), r.parameters.size());
    for (size_t k = 0; k + 1 < r.ranking[f].size(); ++k) {
      auto idx = [&](const std::string& n) { return std::find(r.parameters.begin(), r.parameters.end(), n) - r.parameters.begin(); };
      EXPECT_GE(std::abs(r.relative(f, idx(r.ranking[f][k]))), std::abs(r.relative(f, idx(r.ranking[f][k + 1]))));
    }
  }
}

TEST(Sensitivity, UnknownParameterIsNamed) {
  model::MechanicalJointModel m("middle", model::JointType::Fti, true, 250, 500, 45);
  sensitivity::SensitivityOptions o;
  o.parameters = {"middle.fti.k_Q.flexion"};
  try {
    sensitivity::analyse_sensitivities(m, m.parameters().values(), o);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("middle.fti.k_Q.flexion"), std::string::npos);
  }
}

TEST(Sensitivity, WritesDocumentedHdf5Groups) {
  model::MechanicalJointModel m("middle", model::JointType::Fti, true, 250, 500, 45);
  auto o = options_for(m, sensitivity::Method::Forward);
  o.parameters = {"middle.fti.b_v", "middle.fti.k_E.flexion", "middle.fti.k_F.flexion"};
  auto r = sensitivity::analyse_sensitivities(m, m.parameters().values(), o);
  namespace fs = std::filesystem;
  const std::string file = (fs::temp_directory_path() / ("phasmid_sens_" + std::to_string(::getpid()) + ".h5")).string();
  {
    io::H5Writer w(file);
    w.write_run_info({"", "test"});
    sensitivity::write_sensitivity_h5(w, r);
    w.commit();
  }
  io::H5Reader in(file);
  EXPECT_EQ(in.read_strings("/sensitivity/parameters"), o.parameters);
  auto d = in.read_doubles("/sensitivity/features/middle.fti.angle_max_deg");
  ASSERT_EQ(d.size(), 3u);
  size_t f = r.feature_index("middle.fti.angle_max_deg");
  for (size_t j = 0; j < 3; ++j) EXPECT_DOUBLE_EQ(d[j], r.absolute(f, j));
  auto units = in.read_strings("/sensitivity/units/middle.fti.angle_max_deg");
  EXPECT_EQ(units[0], "deg/(g/s)");
  EXPECT_EQ(units[1], "deg/(mN/mm^2)");
  EXPECT_EQ(in.read_doubles("/sensitivity/relative/period_ms").size(), 3u);
  EXPECT_EQ(in.read_strings("/sensitivity/ranking/period_ms").size(), 3u);
  auto dims = in.dims("/sensitivity/trajectory");
  ASSERT_EQ(dims.size(), 3u);
  EXPECT_EQ(dims[0], r.time.size());
  EXPECT_EQ(dims[1], 2u);
  EXPECT_EQ(dims[2], 3u);
  EXPECT_FALSE(in.read_string_attribute("/sensitivity/features/period_ms", "units").empty());
  fs::remove(file);
}
