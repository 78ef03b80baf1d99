// Residual Jacobians from forward sensitivities (with the scale chain rule) agree with
// central finite differences for every kind of target: kinematic samples with a fitted time
// offset, switch conditions (2.42) with angle, velocity and acceleration, and gait features.
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "fit/fit_problem.hpp"
#include "fit_test_util.hpp"

using namespace phasmid;

namespace {
struct FtiSetup {
  config::Config cfg = config::load_config(fittest::source("configs/fti_mechanical.toml"));
  std::unique_ptr<model::OdeModel> model = config::build_model(cfg);
  fit::ProblemSettings settings;
  FtiSetup() {
    settings.solver = config::simulation_settings(cfg).solver;
    settings.solver.rtol = 1e-11;
    settings.solver.atol = 1e-11;
  }
};

// Max over entries of |J - J_fd| / max(1, |column|_inf of J_fd).
void expect_matches_fd(const fit::FitProblem& p, const std::vector<double>& x, double tol) {
  const size_t m = p.num_residuals(), n = p.num_parameters();
  std::vector<double> r(m), J(m * n), Jfd(m * n);
  std::string err;
  ASSERT_TRUE(p.evaluate(x.data(), r.data(), J.data(), &err)) << err;
  ASSERT_TRUE(p.jacobian_fd(x.data(), Jfd.data(), 1e-4, &err)) << err;
  for (size_t j = 0; j < n; ++j) {
    double scale = 0;
    for (size_t q = 0; q < m; ++q) scale = std::max(scale, std::abs(Jfd[q * n + j]));
    ASSERT_GT(scale, 0.0) << "column " << p.estimated()[j].id << " is zero";
    double worst = 0;
    size_t at = 0;
    for (size_t q = 0; q < m; ++q) {
      double e = std::abs(J[q * n + j] - Jfd[q * n + j]) / scale;
      if (e > worst) {
        worst = e;
        at = q;
      }
    }
    EXPECT_LT(worst, tol) << p.estimated()[j].id << " at residual '" << p.residual_labels()[at] << "': " << J[at * n + j]
                          << " vs fd " << Jfd[at * n + j];
  }
}
}  // namespace

TEST(FitJacobian, KinematicSamplesWithTimeOffsetMatchFiniteDifferences) {
  FtiSetup s;
  fit::Targets t;
  fit::KinematicTarget k;
  k.data = fittest::synthetic_fti({{"middle.fti.b_v", 14.0}}, 900.0, 7.0, 0.3, 3);
  for (auto& tm : k.data.time_ms) tm += 20.0;  // file time = model time + 20 ms
  k.time_offset_parameter = "data.time_offset_ms";
  k.origin = "test";
  t.kinematics.push_back(k);
  auto ps = fittest::fti_parameters(*s.model);
  ps[1].scale = fit::Scale::Lin;  // one of each scale
  ps[2].scale = fit::Scale::Log;
  fit::FitParameter off;
  off.id = "data.time_offset_ms";
  off.lower = -40;
  off.upper = 0;
  off.nominal = -17.3;
  ps.push_back(off);
  fit::FitProblem p(*s.model, ps, t, s.settings);
  auto x = p.start();
  x[0] += 0.02;  // away from the nominal values
  x[4] -= 0.03;
  expect_matches_fd(p, x, 2e-5);
}

TEST(FitJacobian, SwitchConditionsWithVelocityAndAccelerationMatchFiniteDifferences) {
  FtiSetup s;
  fit::Targets t;
  for (auto [time, angle] : {std::pair{250.0, 110.0}, std::pair{500.0, 45.0}, std::pair{750.0, 110.0}}) {
    fit::SwitchCondition c;
    c.channel = "middle.fti";
    c.time_ms = time;
    c.angle_deg = angle;
    c.angle_tolerance_deg = 0.5;
    c.velocity_tolerance_deg_s = 5;
    c.acceleration_tolerance_deg_s2 = 500;
    c.origin = "test";
    t.switches.push_back(c);
  }
  fit::FitProblem p(*s.model, fittest::fti_parameters(*s.model), t, s.settings);
  auto x = p.start();
  x[1] += 0.05;
  expect_matches_fd(p, x, 2e-5);
}

TEST(FitJacobian, FeatureTargetsMatchFiniteDifferences) {
  FtiSetup s;
  fit::Targets t;
  for (auto [name, value] : {std::pair{"middle.fti.angle_max_deg", 110.0}, std::pair{"middle.fti.angle_min_deg", 45.0},
                             std::pair{"middle.fti.flexion_ms", 250.0}}) {
    fit::FeatureTarget f;
    f.feature = name;
    f.value = value;
    f.tolerance = 1.0;
    f.origin = "test";
    t.features.push_back(f);
  }
  s.settings.t_end_ms = 1600;
  s.settings.discard_ms = 400;
  fit::FitProblem p(*s.model, fittest::fti_parameters(*s.model), t, s.settings);
  expect_matches_fd(p, p.start(), 1e-4);
}

TEST(FitJacobian, SwitchTimeAndInitialAngleParametersMatchFiniteDifferences) {
  // Parameters that move the prescribed switches or set the initial state (the solver applies
  // jump conditions / s(0) = dy0/dp): fitting the switching itself from a recording.
  FtiSetup s;
  fit::Targets t;
  fit::KinematicTarget k;
  k.data = fittest::synthetic_fti({{"middle.fti.switch.first_phase_ms", 240.0}}, 900.0, 7.0, 0.3, 5);
  k.origin = "test";
  t.kinematics.push_back(k);
  std::vector<fit::FitParameter> ps;
  for (auto [id, lo, nom, hi] : {std::tuple{"middle.fti.switch.first_phase_ms", 200.0, 250.0, 300.0},
                                 std::tuple{"middle.fti.switch.period_ms", 450.0, 503.0, 550.0},
                                 std::tuple{"middle.fti.gamma0", 40.0, 46.0, 50.0},
                                 std::tuple{"middle.fti.b_v", 5.0, 12.5, 25.0}}) {
    fit::FitParameter p;
    p.id = id;
    p.lower = lo;
    p.nominal = nom;
    p.upper = hi;
    ps.push_back(p);
  }
  fit::FitProblem p(*s.model, ps, t, s.settings);
  expect_matches_fd(p, p.start(), 1e-4);
}

TEST(FitJacobian, TiedParametersSumTheirSensitivities) {
  // '*' in a parameterId ties every matching model parameter to one fitted value.
  FtiSetup s;
  fit::Targets t;
  fit::KinematicTarget k;
  k.data = fittest::synthetic_fti({}, 800.0, 8.0, 0.3, 9);
  k.origin = "test";
  t.kinematics.push_back(k);
  fit::FitParameter tie;
  tie.id = "middle.fti.k_E.*";  // k_E.flexion and k_E.extension share one value
  tie.scale = fit::Scale::Log;
  tie.lower = 100;
  tie.nominal = 900;
  tie.upper = 9000;
  fit::FitParameter bv;
  bv.id = "middle.fti.b_v";
  bv.lower = 5;
  bv.nominal = 12.5;
  bv.upper = 25;
  fit::FitProblem p(*s.model, {tie, bv}, t, s.settings);
  EXPECT_EQ(p.tied_parameters(0), (std::vector<std::string>{"middle.fti.k_E.flexion", "middle.fti.k_E.extension"}));
  auto pm = p.model_parameters(p.start().data());
  EXPECT_NEAR(pm[s.model->parameters().index("middle.fti.k_E.extension")], 900, 1e-9);
  expect_matches_fd(p, p.start(), 2e-5);
}
