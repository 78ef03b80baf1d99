#pragma once
// Shared by the fit tests: a synthetic FTi recording generated with phasmid (Section 3.1
// mechanics, prescribed 1:1 switching, period 500 ms) with known parameters and noise.
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <string>

#include "common/error.hpp"
#include "config/config.hpp"
#include "config/fit_section.hpp"
#include "fit/fit_problem.hpp"
#include "fit/kinematic_data.hpp"
#include "fit/parameter_table.hpp"
#include "build_info.hpp"

namespace phasmid::fittest {

inline std::string source(const std::string& rel) { return std::string(PHASMID_SOURCE_DIR) + "/" + rel; }

// The message of the phasmid::Error that f throws; "" if it throws none.
inline std::string error_message(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

inline const std::vector<std::string>& fti_names() {
  static const std::vector<std::string> n = {"middle.fti.k_E.flexion", "middle.fti.k_F.flexion", "middle.fti.k_E.extension",
                                             "middle.fti.k_F.extension", "middle.fti.b_v"};
  return n;
}

// Simulates configs/fti_mechanical.toml with `truth` and samples gamma every dt_ms up to
// t_end_ms, adding Gaussian noise (sd noise_deg, fixed seed).
inline fit::KinematicData synthetic_fti(const std::map<std::string, double>& truth, double t_end_ms, double dt_ms,
                                        double noise_deg, unsigned seed) {
  auto cfg = config::load_config(source("configs/fti_mechanical.toml"));
  auto m = config::build_model(cfg);
  for (auto& [k, v] : truth) m->parameters().set(k, v);
  solver::Simulator sim(*m, config::simulation_settings(cfg).solver);
  auto r = sim.run(m->parameters().values(), solver::output_grid(t_end_ms, dt_ms));
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> nd(0.0, noise_deg);
  fit::KinematicData d;
  d.channels = {"middle.fti"};
  d.angles_deg.resize(1);
  for (size_t k = 0; k < r.t.size(); ++k) {
    d.time_ms.push_back(r.t[k]);
    d.angles_deg[0].push_back(r.state(k, 0) * 180.0 / M_PI + nd(rng));
  }
  return d;
}

// Log-scaled estimates of the five mechanical parameters within [lo_factor, hi_factor] x start.
inline std::vector<fit::FitParameter> fti_parameters(const model::OdeModel& m, double lo_factor = 0.2, double hi_factor = 5.0) {
  std::vector<fit::FitParameter> ps;
  for (auto& n : fti_names()) {
    fit::FitParameter p;
    p.id = n;
    p.scale = fit::Scale::Log10;
    p.nominal = m.parameters().value(n);
    p.lower = p.nominal * lo_factor;
    p.upper = p.nominal * hi_factor;
    ps.push_back(p);
  }
  return ps;
}

// A shipped fit config loaded as `phasmid fit` loads it: model, [fit] spec and problem.
struct ShippedFit {
  config::Config cfg;
  std::unique_ptr<model::OdeModel> model;
  fit::FitSpec spec;
  std::unique_ptr<fit::FitProblem> problem;
};
inline ShippedFit load_shipped_fit(const std::string& rel) {
  ShippedFit f;
  f.cfg = config::load_config(source(rel));
  f.model = config::build_model(f.cfg);
  f.spec = fit::load_fit_spec(f.cfg, *f.model);
  f.problem = std::make_unique<fit::FitProblem>(*f.model, f.spec.parameters, f.spec.targets, f.spec.problem);
  return f;
}

}  // namespace phasmid::fittest
