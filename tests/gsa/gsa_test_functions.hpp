#pragma once
// The analytic test functions of global sensitivity analysis, reached the way users' models
// are: the registered model kinds "ishigami" and "sobol_g" (src/scenario/kinds/), built from a
// config, evaluated by the scenario (evaluate) or run as a whole analysis on the sweep engine
// (run_gsa: config -> design -> sweep -> HDF5 file -> analysis -> /gsa, read back). Here only
// their exact indices are computed, for comparison.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "config/gsa_inputs.hpp"
#include "gsa/gsa_h5.hpp"
#include "gsa/sampling.hpp"
#include "sweep/sweep_runner.hpp"

namespace gsa_test {

constexpr double kPi = 3.14159265358979323846;

// Ishigami & Homma (1990) with a = 7, b = 0.1 on [-pi, pi]^3: partial variances (Sobol' &
// Levitan 1999) V1, V2, V13 (V3 = V12 = V23 = V123 = 0).
struct Ishigami {
  double a = 7.0, b = 0.1;
  double v1() const { return 0.5 * std::pow(1 + b * std::pow(kPi, 4) / 5, 2); }
  double v2() const { return a * a / 8; }
  double v13() const { return b * b * std::pow(kPi, 8) * (1.0 / 18 - 1.0 / 50); }
  double variance() const { return v1() + v2() + v13(); }
  static std::vector<phasmid::gsa::Parameter> parameters() {
    std::vector<phasmid::gsa::Parameter> ps(3);
    for (int j = 0; j < 3; ++j) ps[j].name = "x" + std::to_string(j + 1), ps[j].unit = "1", ps[j].lower = -kPi, ps[j].upper = kPi;
    return ps;
  }
};

// Sobol' G function on [0,1]^D: V_i = 1 / (3 (1 + a_i)^2), S1_i = V_i / V, V = prod (1 + V_i) - 1.
struct GFunction {
  std::vector<double> a;
  double vi(std::size_t i) const { return 1.0 / (3 * (1 + a[i]) * (1 + a[i])); }
  double variance() const {
    double p = 1;
    for (std::size_t i = 0; i < a.size(); ++i) p *= 1 + vi(i);
    return p - 1;
  }
  double s1(std::size_t i) const { return vi(i) / variance(); }
};

// The scenario of a registered kind, from a config with [model] type = kind.
inline std::unique_ptr<phasmid::scenario::Scenario> scenario_of(const std::string& kind) {
  return phasmid::config::build_scenario(phasmid::config::parse_config("[model]\ntype = \"" + kind + "\"\n", "test"));
}

// Feature `y` of the registered kind at every row of a design in parameter units (rows x dim),
// the first dim parameters of the kind set to the row, the others at their values.
inline std::vector<double> evaluate(const std::string& kind, const std::vector<double>& values, std::size_t dim) {
  const auto s = scenario_of(kind);
  std::vector<double> p = s->parameters().values(), y(values.size() / dim);
  for (std::size_t i = 0; i < y.size(); ++i) {
    for (std::size_t j = 0; j < dim; ++j) p[j] = values[i * dim + j];
    y[i] = s->evaluate_features(p, s->default_settings()).at(0).value;
  }
  return y;
}

// A whole analysis in-process on the sweep engine: the config's design swept into a
// temporary file, analysed from that file, and the /gsa group read back.
inline phasmid::gsa::GsaResult run_gsa(const phasmid::config::Config& cfg, const std::string& file, int threads = 2) {
  const auto path = (std::filesystem::temp_directory_path() / file).string();
  std::filesystem::remove(path);
  const phasmid::gsa::GsaInputs in = phasmid::config::gsa_inputs(cfg, {});
  phasmid::sweep::SweepOptions o;
  o.output = path, o.threads = threads, o.progress = false;
  if (!phasmid::sweep::run_sweep(in.sweep, o).complete) throw phasmid::Error("test sweep did not complete");
  phasmid::gsa::analyse_and_write(in, path, path, "test");
  return phasmid::gsa::read_gsa_h5(phasmid::io::H5Reader(path));
}

}  // namespace gsa_test
