// Limit-cycle analysis against analytic values: the Stuart-Landau (Hopf normal form)
// oscillator with an extra decaying state has Floquet multipliers 1, exp(-2 lambda T) and
// exp(-mu T), and (with isochrons along rays) an exactly known phase response curve.
// The monodromy matrix of the forced mechanical FTi joint is checked against central
// differences of the initial state.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>

#include <unistd.h>

#include <cstdio>

#include "io/h5_file.hpp"
#include "model/mechanical_joint_model.hpp"
#include "sensitivity/floquet.hpp"

using namespace phasmid;

namespace {

// x' = lambda x (1 - r^2) - omega y,  y' = lambda y (1 - r^2) + omega x,  z' = -mu z.
// Limit cycle r = 1 with period 2 pi / omega; the phase angle advances at omega everywhere.
class StuartLandau : public model::OdeModelT<StuartLandau> {
 public:
  StuartLandau(double lambda, double omega, double mu) {
    il_ = params_.add({"sl.lambda", lambda, "1/ms", "test", "growth rate"});
    iw_ = params_.add({"sl.omega", omega, "rad/ms", "test", "angular frequency"});
    im_ = params_.add({"sl.mu", mu, "1/ms", "test", "decay of z"});
    add_state("sl.x", "1");
    add_state("sl.y", "1");
    add_state("sl.z", "1");
  }
  std::string kind() const override { return "stuart_landau"; }
  std::vector<double> initial_state(const std::vector<double>&) const override { return {0.5, 0.0, 1.0}; }
  template <class T>
  void eval(double, const T* y, const T* p, T* ydot) const {
    T g = p[il_] * (1.0 - (y[0] * y[0] + y[1] * y[1]));
    ydot[0] = g * y[0] - p[iw_] * y[1];
    ydot[1] = g * y[1] + p[iw_] * y[0];
    ydot[2] = -p[im_] * y[2];
  }

 private:
  size_t il_, iw_, im_;
};

const double kLambda = 0.005, kOmega = 2 * M_PI / 100.0, kMu = 0.02;

sensitivity::FloquetOptions sl_options() {
  sensitivity::FloquetOptions o;
  o.section = {1, 0.0, +1};  // y = 0 rising: theta = 0
  o.transient_ms = 4000;
  o.max_period_ms = 150;
  o.solver.rtol = o.solver.atol = 1e-11;
  return o;
}

}  // namespace

TEST(Floquet, StuartLandauMultipliersMatchAnalyticValues) {
  StuartLandau m(kLambda, kOmega, kMu);
  auto res = sensitivity::floquet_analysis(m, m.parameters().values(), sl_options());
  const double T = 2 * M_PI / kOmega;
  EXPECT_NEAR(res.orbit.period_ms, T, 1e-6);
  EXPECT_NEAR(res.orbit.y0[0], 1.0, 1e-6);  // on the unit circle at theta = 0
  EXPECT_NEAR(res.orbit.y0[1], 0.0, 1e-8);
  ASSERT_EQ(res.multipliers.size(), 3u);
  EXPECT_NEAR(res.multipliers[0].real(), 1.0, 1e-6);  // the phase direction
  EXPECT_NEAR(res.multipliers[1].real(), std::exp(-2 * kLambda * T), 1e-6);
  EXPECT_NEAR(res.multipliers[2].real(), std::exp(-kMu * T), 1e-6);
  for (auto& mu : res.multipliers) EXPECT_NEAR(mu.imag(), 0.0, 1e-8);
  EXPECT_LT(res.trivial_multiplier_error, 1e-6);
  EXPECT_LT(res.closure_error, 1e-6);
  // The eigenvector of the multiplier 1 is the flow direction f(y0) = (0, omega, 0) at theta = 0:
  // Phi f(y0) = f(y0).
  Eigen::Vector3d f(0.0, kOmega, 0.0);
  Eigen::Vector3d pf = res.monodromy * f;
  EXPECT_NEAR((pf - f).norm() / f.norm(), 0.0, 1e-6);
}

TEST(Floquet, StuartLandauPhaseResponseCurveIsExact) {
  // Phase depends on the angle only, so a kick dx at theta shifts the phase by
  // atan2(sin theta, cos theta + dx) - theta (radians), for any kick size.
  StuartLandau m(kLambda, kOmega, kMu);
  sensitivity::PrcOptions o;
  o.state = 0;
  o.amplitude = 0.05;
  o.n_phases = 16;
  o.cycles_after = 3;
  o.floquet = sl_options();
  auto prc = sensitivity::phase_response_curve(m, m.parameters().values(), o);
  ASSERT_EQ(prc.phase.size(), 16u);
  double largest = 0;
  for (size_t k = 0; k < prc.phase.size(); ++k) {
    const double th = 2 * M_PI * prc.phase[k];
    const double expected = (std::atan2(std::sin(th), std::cos(th) + o.amplitude) - th);
    const double wrapped = std::remainder(expected, 2 * M_PI) / (2 * M_PI);
    EXPECT_NEAR(prc.shift[k], wrapped, 1e-6) << "phase " << prc.phase[k];
    largest = std::max(largest, std::abs(wrapped));
  }
  EXPECT_GT(largest, 0.007);  // the curve is not trivially zero (~ amplitude / 2 pi)
}

TEST(Floquet, MonodromyOfForcedMechanicalJointMatchesCentralDifferences) {
  // The prescribed-switching FTi joint is a forced, damped system: its cycle is the forcing
  // cycle (period 500 ms) and both multipliers lie inside the unit circle.
  model::MechanicalJointModel m("middle", model::JointType::Fti, true, 250, 500, 45);
  auto p = m.parameters().values();
  sensitivity::FloquetOptions o;
  o.section = sensitivity::default_section(m);
  o.transient_ms = 2000;
  o.max_period_ms = 600;
  o.solver.rtol = o.solver.atol = 1e-10;
  auto res = sensitivity::floquet_analysis(m, p, o);
  EXPECT_NEAR(res.orbit.period_ms, 500.0, 1e-5);
  for (auto& mu : res.multipliers) EXPECT_LT(std::abs(mu), 0.99);
  const size_t n = m.num_states();
  for (size_t j = 0; j < n; ++j) {
    // The cycle contracts by ~1e-5 per period, so the differences of the perturbed end states
    // are small (2 h Phi ~ 1e-8 at h = 1e-4, only ~100x the integration error at tolerance
    // 1e-10: Phi(1,1) then deviates by 0.8 %). h = 1e-3 puts them 1000x above it while the
    // truncation error stays small (worst entry 0.19 %; 0.3 % at 1e-2, 23 % at 1e-1).
    const double h = 1e-3 * std::max(1.0, std::abs(res.orbit.y0[j]));
    std::vector<double> yp = res.orbit.y0, ym = res.orbit.y0;
    yp[j] += h;
    ym[j] -= h;
    sensitivity::InitialValueModel a(m, yp, res.orbit.t0), b(m, ym, res.orbit.t0);
    auto ra = solver::Simulator(a, o.solver).run(a.extend(p), {0.0, res.orbit.period_ms});
    auto rb = solver::Simulator(b, o.solver).run(b.extend(p), {0.0, res.orbit.period_ms});
    for (size_t i = 0; i < n; ++i) {
      const double fd = (ra.state(1, i) - rb.state(1, i)) / (2 * h);
      EXPECT_NEAR(res.monodromy(i, j), fd, 0.01 * std::abs(fd)) << "Phi(" << i << "," << j << ")";
    }
  }
}

TEST(Floquet, WritesFloquetAndPrcGroups) {
  StuartLandau m(kLambda, kOmega, kMu);
  auto p = m.parameters().values();
  auto res = sensitivity::floquet_analysis(m, p, sl_options());
  sensitivity::PrcOptions o;
  o.n_phases = 4;
  o.cycles_after = 2;
  o.amplitude = 0.05;
  o.floquet = sl_options();
  auto prc = sensitivity::phase_response_curve(m, p, o);
  const std::string file = "/tmp/phasmid_floquet_" + std::to_string(::getpid()) + ".h5";
  {
    io::H5Writer w(file);
    sensitivity::write_floquet_h5(w, m, res);
    sensitivity::write_prc_h5(w, m, o, prc);
    w.commit();
  }
  io::H5Reader in(file);
  auto ab = in.read_doubles("/sensitivity/floquet/multipliers_abs");
  ASSERT_EQ(ab.size(), 3u);
  EXPECT_NEAR(ab[1], std::exp(-2 * kLambda * 100.0), 1e-6);
  EXPECT_EQ(in.dims("/sensitivity/floquet/monodromy"), (std::vector<hsize_t>{3, 3}));
  EXPECT_NEAR(in.read_doubles("/sensitivity/floquet/period_ms")[0], 100.0, 1e-6);
  EXPECT_EQ(in.read_doubles("/sensitivity/prc/shift"), prc.shift);
  EXPECT_EQ(in.read_string_attribute("/sensitivity/prc", "state"), "sl.x");
  std::remove(file.c_str());
}
