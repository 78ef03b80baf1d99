// Gait features from located events: an oscillator with analytic extrema and phase
// durations, the Section 3.1 mechanical FTi joint against densely sampled output, and the
// /features HDF5 round trip through `phasmid features`.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "features/features.hpp"
#include "io/h5_file.hpp"
#include "model/mechanical_joint_model.hpp"
#include "build_info.hpp"

using namespace phasmid;

namespace {

// theta = c - A cos(phi) with phi' = Omega (1 + eps sin phi): a joint angle whose increasing
// half-cycle (phi in [0, pi]) and decreasing half-cycle take different times.
//   T_inc = 2/(Omega s) (pi/2 - atan(eps/s)),  T_dec = 2/(Omega s) (pi/2 + atan(eps/s)),
//   s = sqrt(1 - eps^2), period = 2 pi / (Omega s), extrema c +- A.
class WarpedOscillator : public model::OdeModelT<WarpedOscillator> {
 public:
  WarpedOscillator(double omega, double eps, double A_deg, double c_deg) {
    iw_ = params_.add({"test.omega", omega, "rad/ms", "test", "angular frequency"});
    ie_ = params_.add({"test.eps", eps, "1", "test", "asymmetry"});
    ia_ = params_.add({"test.A", A_deg * M_PI / 180, "rad", "test", "amplitude"});
    ic_ = params_.add({"test.c", c_deg * M_PI / 180, "rad", "test", "centre"});
    add_state("test.phi", "rad");
    size_t a = add_state("middle.fti.gamma", "rad");
    size_t v = add_state("middle.fti.gamma_dot", "rad/ms");
    angles_.push_back({"middle", "fti", a, v});
  }
  std::string kind() const override { return "test"; }
  std::vector<double> initial_state(const std::vector<double>& p) const override { return {0.0, p[ic_] - p[ia_], 0.0}; }
  template <class T>
  void eval(double, const T* y, const T* p, T* ydot) const {
    using std::cos;
    using std::sin;
    T phidot = p[iw_] * (1.0 + p[ie_] * sin(y[0]));
    ydot[0] = phidot;
    ydot[1] = y[2];
    // d/dt [A sin(phi) phidot] with phidot' = Omega eps cos(phi) phidot
    ydot[2] = p[ia_] * phidot * cos(y[0]) * (phidot + p[iw_] * p[ie_] * sin(y[0]));
  }

 private:
  size_t iw_, ie_, ia_, ic_;
};

// Two joints: theta1 = c - A cos(Omega t) and theta2 = theta1 through a first-order low-pass
// (time constant tau), whose steady state lags by atan(Omega tau) / (2 pi) cycles.
class LowPassPair : public model::OdeModelT<LowPassPair> {
 public:
  LowPassPair(double omega, double tau) {
    iw_ = params_.add({"test.omega", omega, "rad/ms", "test", "angular frequency"});
    it_ = params_.add({"test.tau", tau, "ms", "test", "low-pass time constant"});
    ia_ = params_.add({"test.A", 0.5, "rad", "test", "amplitude"});
    ic_ = params_.add({"test.c", 1.4, "rad", "test", "centre"});
    add_state("test.phi", "rad");
    angles_.push_back({"middle", "fti", add_state("middle.fti.gamma", "rad"), add_state("middle.fti.gamma_dot", "rad/ms")});
    angles_.push_back({"middle", "ctr", add_state("middle.ctr.beta", "rad"), add_state("middle.ctr.beta_dot", "rad/ms")});
  }
  std::string kind() const override { return "test"; }
  std::vector<double> initial_state(const std::vector<double>& p) const override {
    return {0.0, p[ic_] - p[ia_], 0.0, p[ic_] - p[ia_], 0.0};
  }
  template <class T>
  void eval(double, const T* y, const T* p, T* ydot) const {
    using std::cos;
    ydot[0] = p[iw_];
    ydot[1] = y[2];
    ydot[2] = p[ia_] * p[iw_] * p[iw_] * cos(y[0]);
    ydot[3] = y[4];
    ydot[4] = (y[2] - y[4]) / p[it_];
  }

 private:
  size_t iw_, it_, ia_, ic_;
};

double find(const std::vector<features::Feature>& fs, const std::string& name) {
  for (auto& f : fs)
    if (f.name == name) return f.value;
  ADD_FAILURE() << "feature " << name << " missing";
  return NAN;
}

std::string unit_of(const std::vector<features::Feature>& fs, const std::string& name) {
  for (auto& f : fs)
    if (f.name == name) return f.unit;
  return "";
}

}  // namespace

TEST(Features, WarpedOscillatorMatchesAnalyticPhaseDurations) {
  const double omega = 2 * M_PI / 400.0, eps = 0.4;
  WarpedOscillator m(omega, eps, 30.0, 80.0);
  solver::SolverOptions so;
  so.rtol = so.atol = 1e-11;
  auto r = solver::Simulator(m, so).run(m.parameters().values(), solver::output_grid(3000, 10), features::feature_roots(m));
  auto fs = features::compute_features(m, r, {});
  const double s = std::sqrt(1 - eps * eps);
  const double T = 2 * M_PI / (omega * s);
  const double t_inc = 2 / (omega * s) * (M_PI / 2 - std::atan(eps / s));
  const double t_dec = 2 / (omega * s) * (M_PI / 2 + std::atan(eps / s));
  EXPECT_NEAR(find(fs, "period_ms"), T, 1e-6 * T);
  EXPECT_NEAR(find(fs, "middle.fti.period_ms"), T, 1e-6 * T);
  EXPECT_NEAR(find(fs, "middle.fti.flexion_ms"), t_inc, 1e-6 * T);
  EXPECT_NEAR(find(fs, "middle.fti.extension_ms"), t_dec, 1e-6 * T);
  EXPECT_NEAR(find(fs, "middle.fti.flexion_fraction"), t_inc / T, 1e-8);
  EXPECT_NEAR(find(fs, "middle.fti.phase_ratio"), t_inc / t_dec, 1e-7);
  // The angle is integrated from its velocity, so it carries the accumulated integration
  // error (~1e-5 deg after 3 s at tolerance 1e-11), unlike the phase-derived event times.
  EXPECT_NEAR(find(fs, "middle.fti.angle_max_deg"), 110.0, 1e-4);
  EXPECT_NEAR(find(fs, "middle.fti.angle_min_deg"), 50.0, 1e-4);
  EXPECT_EQ(unit_of(fs, "middle.fti.flexion_ms"), "ms");
  EXPECT_EQ(unit_of(fs, "middle.fti.angle_max_deg"), "deg");
  EXPECT_EQ(unit_of(fs, "middle.fti.phase_ratio"), "1");
}

TEST(Features, WarpedOscillatorFeatureGradientsMatchAnalyticDerivatives) {
  // d period / d omega = -period / omega; d period / d eps = period * eps / (1 - eps^2);
  // extremal angles do not depend on omega or eps.
  const double omega = 2 * M_PI / 400.0, eps = 0.4;
  WarpedOscillator m(omega, eps, 30.0, 80.0);
  solver::SolverOptions so;
  so.rtol = so.atol = 1e-11;
  auto p = m.parameters().values();
  auto r = solver::Simulator(m, so).run(p, solver::output_grid(3000, 10), features::feature_roots(m), {0, 1});
  auto g = features::compute_feature_gradients(m, r, {});
  const double s = std::sqrt(1 - eps * eps), T = 2 * M_PI / (omega * s);
  const double a = std::atan(eps / s);
  // t_inc = 2/(omega s) (pi/2 - a(eps)); da/deps = 1/s (derivative of asin(eps)).
  const double dtinc_deps = 2 / omega * (eps / (s * s * s) * (M_PI / 2 - a) - 1 / (s * s));
  bool seen = false;
  for (auto& f : g) {
    if (f.feature.name == "middle.fti.period_ms") {
      EXPECT_NEAR(f.gradient[0], -T / omega, 1e-6 * T / omega);
      EXPECT_NEAR(f.gradient[1], T * eps / (1 - eps * eps), 1e-6 * T);
      seen = true;
    }
    if (f.feature.name == "middle.fti.flexion_ms") EXPECT_NEAR(f.gradient[1], dtinc_deps, 1e-5 * std::abs(dtinc_deps));
    if (f.feature.name == "middle.fti.angle_max_deg") {
      // Zero up to the integration error of the angle: relative sensitivity p/F dF/dp < 1e-6.
      EXPECT_LT(std::abs(f.gradient[0] * omega / f.feature.value), 1e-6);
      EXPECT_LT(std::abs(f.gradient[1] * eps / f.feature.value), 1e-6);
    }
  }
  EXPECT_TRUE(seen);
}

TEST(Features, MechanicalFtiExtremaFromEventsMatchDenseSampling) {
  // Fig. 3.1A: 250 ms flexion / 250 ms extension from 45 deg at rest. The located extrema are
  // the overshoot peaks (113.09 deg shortly after 130 ms into flexion, 39.92 deg in extension).
  model::MechanicalJointModel m("middle", model::JointType::Fti, true, 250, 500, 45);
  solver::SolverOptions so;
  so.rtol = so.atol = 1e-10;
  auto p = m.parameters().values();
  auto r = solver::Simulator(m, so).run(p, solver::output_grid(3000, 0.01), features::feature_roots(m));
  features::FeatureOptions fo;
  fo.discard_ms = 500;
  auto fs = features::compute_features(m, r, fo);
  // Dense sampling of the last full cycle [2500, 3000].
  double amax = -1e9, amin = 1e9, tmax = 0, tmin = 0;
  for (size_t k = 0; k < r.t.size(); ++k) {
    if (r.t[k] < 2500) continue;
    double a = r.state(k, 0) * 180 / M_PI;
    if (a > amax) amax = a, tmax = r.t[k];
    if (a < amin) amin = a, tmin = r.t[k];
  }
  EXPECT_NEAR(find(fs, "middle.fti.angle_max_deg"), amax, 1e-4);
  EXPECT_NEAR(find(fs, "middle.fti.angle_min_deg"), amin, 1e-4);
  EXPECT_NEAR(find(fs, "middle.fti.angle_max_deg"), 113.09, 0.01);
  EXPECT_NEAR(find(fs, "middle.fti.angle_min_deg"), 39.92, 0.01);
  // Prescribed switching: the cycle repeats with the forcing period.
  EXPECT_NEAR(find(fs, "period_ms"), 500.0, 1e-4);
  // Durations between the sampled extrema (to the sampling step).
  double inc = (tmax - 2500) + (3000 - tmin);  // min (~2866) to the next max (~3134), by periodicity
  EXPECT_NEAR(find(fs, "middle.fti.flexion_ms"), inc, 0.02);
  EXPECT_NEAR(find(fs, "middle.fti.extension_ms"), tmin - tmax, 0.02);
  EXPECT_NEAR(find(fs, "middle.fti.flexion_ms") + find(fs, "middle.fti.extension_ms"), 500.0, 1e-4);
}

TEST(Features, DampedOscillationsWithinAPhaseAreNotCycles) {
  // The mechanical CTr joint rings around its equilibrium within each phase (several small
  // velocity zeros per phase); only one maximum and one minimum per 500 ms cycle are kept.
  model::MechanicalJointModel m("middle", model::JointType::Ctr, true, 188, 500, 30);
  auto r = solver::Simulator(m).run(m.parameters().values(), solver::output_grid(2500, 1), features::feature_roots(m));
  size_t raw = 0;
  for (auto& e : r.events) raw += e.t >= 500;
  features::FeatureOptions fo;
  fo.discard_ms = 500;
  auto fs = features::compute_features(m, r, fo);
  EXPECT_GT(raw, 12u);  // many raw extrema ...
  EXPECT_NEAR(find(fs, "middle.ctr.period_ms"), 500.0, 1e-4);  // ... one cycle per forcing period
  EXPECT_NEAR(find(fs, "middle.ctr.levation_ms") + find(fs, "middle.ctr.depression_ms"), 500.0, 1e-4);
}

TEST(Features, TooShortRunOmitsPeriod) {
  model::MechanicalJointModel m("middle", model::JointType::Fti, true, 250, 500, 45);
  auto r = solver::Simulator(m).run(m.parameters().values(), solver::output_grid(400, 1), features::feature_roots(m));
  auto fs = features::compute_features(m, r, {});
  for (auto& f : fs) EXPECT_NE(f.name, "period_ms");
}

TEST(FeaturesVerb, PrintsTableAndJsonFromH5) {
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / ("phasmid_features_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string file = (dir / "run.h5").string();
  {
    io::H5Writer w(file);
    w.write_run_info({"[model]\n", "test"});
    features::write_features_h5(w, {{"period_ms", 500.0, "ms"}, {"middle.fti.angle_max_deg", 113.09, "deg"}});
    w.commit();
  }
  {
    io::H5Reader rd(file);
    auto back = features::read_features_h5(rd);
    ASSERT_EQ(back.size(), 2u);
  }
  const std::string out = (dir / "out.json").string(), err = (dir / "err.txt").string();
  int rc = std::system((std::string(PHASMID_BINARY) + " features " + file + " --json > " + out).c_str());
  ASSERT_EQ(rc, 0);
  std::ifstream in(out);
  nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_TRUE(j.is_array());
  ASSERT_EQ(j.size(), 2u);
  bool found = false;
  for (auto& e : j)
    if (e["name"] == "period_ms") {
      EXPECT_DOUBLE_EQ(e["value"].get<double>(), 500.0);
      EXPECT_EQ(e["unit"], "ms");
      found = true;
    }
  EXPECT_TRUE(found);
  rc = std::system((std::string(PHASMID_BINARY) + " features " + file + " > " + out).c_str());
  EXPECT_EQ(rc, 0);
  std::stringstream table;
  table << std::ifstream(out).rdbuf();
  EXPECT_NE(table.str().find("middle.fti.angle_max_deg"), std::string::npos);

  // Missing file and a non-phasmid file: non-zero exit, one line on stderr.
  rc = std::system((std::string(PHASMID_BINARY) + " features " + (dir / "nope.h5").string() + " 2> " + err).c_str());
  EXPECT_NE(rc, 0);
  std::stringstream e1;
  e1 << std::ifstream(err).rdbuf();
  const std::string msg = e1.str();
  EXPECT_NE(msg.find("no such file"), std::string::npos);
  EXPECT_EQ(std::count(msg.begin(), msg.end(), '\n'), 1);
  {
    std::ofstream junk(dir / "junk.h5");
    junk << "not hdf5";
  }
  rc = std::system((std::string(PHASMID_BINARY) + " features " + (dir / "junk.h5").string() + " 2> " + err).c_str());
  EXPECT_NE(rc, 0);
  auto stderr_of = [&](const std::string& file) {
    int code = std::system((std::string(PHASMID_BINARY) + " features " + file + " 2> " + err).c_str());
    EXPECT_NE(code, 0) << file;
    std::stringstream ss;
    ss << std::ifstream(err).rdbuf();
    return ss.str();
  };
  {
    io::H5Writer w((dir / "foreign.h5").string());  // HDF5, but not written by phasmid
    w.write_scalar("/x", 1.0, "1");
    w.commit();
  }
  EXPECT_NE(stderr_of((dir / "foreign.h5").string()).find("not a phasmid file"), std::string::npos);
  {
    io::H5Writer w((dir / "nofeatures.h5").string());
    w.write_run_info({"", "test"});
    w.commit();
  }
  EXPECT_NE(stderr_of((dir / "nofeatures.h5").string()).find("no /features"), std::string::npos);
  fs::remove_all(dir);
}

TEST(Features, PhaseLagOfALowPassFilteredJointMatchesAnalyticValue) {
  const double omega = 2 * M_PI / 400.0, tau = 20.0;
  LowPassPair m(omega, tau);
  solver::SolverOptions so;
  so.rtol = so.atol = 1e-11;
  auto p = m.parameters().values();
  auto r = solver::Simulator(m, so).run(p, solver::output_grid(4000, 10), features::feature_roots(m), {0, 1});
  features::FeatureOptions fo;
  fo.discard_ms = 1200;  // the filter's transient decays like exp(-t / 20 ms)
  auto fs = features::compute_features(m, r, fo);
  const double x = omega * tau, lag = std::atan(x) / (2 * M_PI);
  EXPECT_NEAR(find(fs, "middle.ctr.phase_lag"), lag, 1e-7);
  EXPECT_NEAR(find(fs, "middle.ctr.period_ms"), 400.0, 1e-6);
  for (auto& g : features::compute_feature_gradients(m, r, fo)) {
    if (g.feature.name != "middle.ctr.phase_lag") continue;
    EXPECT_NEAR(g.gradient[0], tau / (1 + x * x) / (2 * M_PI), 1e-5 * tau / (2 * M_PI));  // d lag / d omega
    EXPECT_NEAR(g.gradient[1], omega / (1 + x * x) / (2 * M_PI), 1e-5 * omega / (2 * M_PI));  // d lag / d tau
  }
}
