#pragma once
// Small but realistic phasmid HDF5 files of each kind, written with H5Writer, for the report
// tests (no Python needed). Shapes and names follow docs/hdf5.md.
#include <cmath>
#include <string>
#include <vector>

#include "io/h5_file.hpp"
#include "sweep/ranges.hpp"

namespace phasmid::testing {

inline io::RunInfo fixture_info(const std::string& kind) {
  return {"# fixture config for a " + kind + " report test\n[model]\nname = \"<fixture & test>\"\n",
          "phasmid test-fixture " + kind};
}

inline void write_parameters_and_features(io::H5Writer& w) {
  w.write("/parameters/names", std::vector<std::string>{"middle.fti.k_E.flexion", "middle.fti.k_F.flexion",
                                                         "middle.fti.b_v", "middle.fti.cpg.tau"});
  w.write("/parameters/values", std::vector<double>{0.0021, 0.0034, 0.00012, 50.0}, "mixed");
  w.write("/parameters/units", std::vector<std::string>{"mN mm/deg", "mN mm/deg", "mN mm s/deg", "ms"});
  w.write_scalar("/features/period_ms", 1012.5, "ms");
  w.write_scalar("/features/stance_duration_ms", 640.25, "ms");
  w.write_scalar("/features/swing_duration_ms", 372.25, "ms");
  w.write_scalar("/features/middle.fti.max_deg", 118.4, "deg");
  w.write_scalar("/features/middle.fti.min_deg", 61.2, "deg");
}

// 6001 samples (> 5000: exercises decimation), three legs, CPG/MN potentials, footfall.
inline void write_trajectory_fixture(const std::string& path) {
  io::H5Writer w(path);
  w.write_run_info(fixture_info("trajectory"));
  const int n = 6001;
  const double dt = 0.5, period = 1000.0, pi = 3.141592653589793;
  std::vector<double> t(n);
  for (int i = 0; i < n; ++i) t[i] = i * dt;
  w.write("/trajectory/time", t, "ms");
  const std::vector<std::string> legs = {"front", "middle", "hind"};
  const std::vector<std::string> joints = {"thc", "ctr", "fti"};
  for (std::size_t l = 0; l < legs.size(); ++l) {
    const double lag = 0.5 * l;  // tripod-like phase lags
    for (std::size_t j = 0; j < joints.size(); ++j) {
      std::vector<double> a(n);
      for (int i = 0; i < n; ++i) a[i] = 90 + (25 - 5 * j) * std::sin(2 * pi * (t[i] / period - lag) + 0.4 * j);
      w.write("/trajectory/angles/" + legs[l] + "/" + joints[j], a, "deg");
      if (legs[l] == "middle") {
        std::vector<double> v(n);
        for (int i = 0; i < n; ++i) v[i] = 1000 * (25 - 5 * j) * 2 * pi / period * std::cos(2 * pi * (t[i] / period - lag) + 0.4 * j);
        w.write("/trajectory/angular_velocity/middle/" + joints[j], v, "deg/s");
      }
    }
    std::vector<double> foot(n);
    for (int i = 0; i < n; ++i) foot[i] = std::sin(2 * pi * (t[i] / period - lag)) > 0.3 ? 1.0 : 0.0;
    w.write("/trajectory/footfall/" + legs[l], foot, "1");
  }
  for (const auto& joint : joints) {
    for (const char* unit : {"C1", "C2", "MN1", "MN2"}) {
      std::vector<double> v(n), wv(n);
      const double shift = unit[0] == 'M' ? 0.1 : 0.0, sign = (unit[1] == '1' || unit[2] == '1') ? 1 : -1;
      for (int i = 0; i < n; ++i) {
        double s = sign * std::sin(2 * pi * (t[i] / period - shift));
        v[i] = -60 + 20 * std::tanh(4 * s) + (s > 0.95 ? 30 : 0);  // a few spike-like peaks
        wv[i] = 0.5 + 0.5 * s;
      }
      w.write("/trajectory/states/middle." + joint + "." + unit + ".V", v, "mV");
      w.write("/trajectory/states/middle." + joint + "." + unit + ".w", wv, "1");
    }
  }
  {  // an interneuron: drawn as an "other" potential
    std::vector<double> v(n);
    for (int i = 0; i < n; ++i) v[i] = -55 + 10 * std::sin(2 * pi * t[i] / period);
    w.write("/trajectory/states/middle.fti.in_ext.V", v, "mV");
  }
  write_parameters_and_features(w);
  w.write("/unknown_extension/stuff", std::vector<double>{1, 2, 3}, "1");  // must be ignored gracefully
  w.commit();
}

// Cruse (1980)-style file: positions and protraction flags of six legs.
inline void write_cruse_fixture(const std::string& path) {
  io::H5Writer w(path);
  w.write_run_info(fixture_info("cruse"));
  const int n = 2000;
  std::vector<double> t(n);
  for (int i = 0; i < n; ++i) t[i] = i * 2.0;
  w.write("/trajectory/time", t, "ms");
  const std::vector<std::string> legs = {"L1", "L2", "L3", "R1", "R2", "R3"};
  for (std::size_t l = 0; l < legs.size(); ++l) {
    std::vector<double> pos(n), pro(n);
    double x = 0;
    bool protract = false;
    const double lo = -1.0 + 0.1 * l, hi = 1.0;
    for (int i = 0; i < n; ++i) {
      x += protract ? 0.02 : -0.006;
      if (x <= lo) protract = true;
      if (x >= hi) protract = false;
      pos[i] = x;
      pro[i] = protract ? 1 : 0;
    }
    w.write("/trajectory/position/" + legs[l], pos, "1");
    w.write("/trajectory/protraction/" + legs[l], pro, "1");
    w.write("/events/protraction_onset/" + legs[l], std::vector<double>{100.0 + l, 520.0 + l}, "ms");
  }
  w.write_scalar("/features/period_ms", 420.0, "ms");
  w.write("/features/phase", std::vector<double>{0, 0.33, 0.67, 0.5, 0.83, 0.17}, "1");
  w.write("/features/in_phase_pairs", std::vector<std::string>{"L1-R2", "L3-R2"});
  w.commit();
}

// A one-at-a-time sweep with its range analysis, as `phasmid sweep` writes it for
// configs/cruse1980_table1.toml: two parameters each over its own axis, /sweep/ranges from the
// sweep code's own functions. T1 is in range at 4..7 (contiguous), T2 at 1..2 and 4 (a gap).
inline void write_range_sweep_fixture(const std::string& path) {
  io::H5Writer w(path);
  w.write_run_info(fixture_info("range sweep"));
  sweep::SweepSpec spec;
  spec.design = sweep::Design::OneAtATime;
  spec.parameters = {{"T1", "unit", {2, 3, 4, 5, 6, 7, 8}, 0, 0, false, 7.0, 0},
                     {"T2", "unit", {0, 1, 2, 3, 4, 5}, 0, 0, false, 5.5, 1}};
  std::vector<double> points, stable, period;
  for (std::size_t d = 0; d < 2; ++d)
    for (double v : spec.parameters[d].values) {
      points.push_back(d == 0 ? v : 7.0);
      points.push_back(d == 1 ? v : 5.5);
      const bool in = d == 0 ? (v >= 4 && v <= 7) : (v == 1 || v == 2 || v == 4);
      stable.push_back(in ? 1 : 0);
      period.push_back(1000 + 10 * v);
    }
  const auto n = static_cast<hsize_t>(stable.size());
  w.write("/sweep/parameter_names", std::vector<std::string>{"T1", "T2"});
  w.write("/sweep/parameter_units", std::vector<std::string>{"unit", "unit"});
  w.write("/sweep/points", points, "unit", {n, 2});
  w.write("/sweep/features/table1_stable", stable, "1");
  w.write("/sweep/features/period_ms", period, "ms");
  w.write("/sweep/gait_class", std::vector<std::string>(n, "ok"));
  w.write("/sweep/status", std::vector<std::string>(n, "ok"));
  w.set_attribute("/sweep", "design", "one_at_a_time");
  sweep::write_ranges_h5(w, "table1_stable", sweep::one_at_a_time_ranges(spec, stable));
  w.commit();
}

inline void write_sensitivity_fixture(const std::string& path) {
  io::H5Writer w(path);
  w.write_run_info(fixture_info("sensitivity"));
  const std::vector<std::string> params = {"middle.fti.k_E.flexion", "middle.fti.k_F.flexion",
                                           "middle.fti.k_E.extension", "middle.fti.k_F.extension",
                                           "middle.fti.b_v", "middle.fti.cpg.tau", "middle.fti.cpg.g_syn",
                                           "middle.fti.mn.gain"};
  w.write("/sensitivity/parameters", params);
  const std::vector<std::pair<std::string, std::string>> feats = {
      {"period_ms", "ms"}, {"stance_duration_ms", "ms"}, {"swing_duration_ms", "ms"}, {"middle.fti.max_deg", "deg"}};
  for (std::size_t f = 0; f < feats.size(); ++f) {
    std::vector<double> raw(params.size()), rel(params.size());
    for (std::size_t p = 0; p < params.size(); ++p) {
      rel[p] = std::sin(1.7 * p + 2.3 * f) * std::exp(-0.25 * p);
      raw[p] = rel[p] * 1000.0 / (1 + p);
    }
    w.write("/sensitivity/features/" + feats[f].first, raw, feats[f].second + " per parameter unit");
    w.write("/sensitivity/relative/" + feats[f].first, rel, "1");
  }
  w.write("/sensitivity/floquet/multipliers_real", std::vector<double>{1.0, 0.42, 0.11, 0.11}, "1");
  w.write("/sensitivity/floquet/multipliers_imag", std::vector<double>{0.0, 0.0, 0.35, -0.35}, "1");
  w.write("/sensitivity/parameter_units", std::vector<std::string>(params.size(), "1"));
  std::vector<double> phase, shift;
  for (int i = 0; i < 40; ++i) {
    phase.push_back(i / 40.0);
    shift.push_back(0.05 * std::sin(2 * 3.141592653589793 * i / 40.0) + 0.01);
  }
  w.write("/sensitivity/prc/phase", phase, "cycles");
  w.write("/sensitivity/prc/shift", shift, "cycles (positive = advance)");
  w.set_attribute("/sensitivity/prc", "state", "middle.fti.C1.V");
  write_parameters_and_features(w);
  w.commit();
}

inline void write_fit_fixture(const std::string& path) {
  io::H5Writer w(path);
  w.write_run_info(fixture_info("fit"));
  const std::vector<std::string> names = {"middle.fti.k_E.flexion", "middle.fti.k_F.flexion",
                                          "middle.fti.k_E.extension", "middle.fti.k_F.extension", "middle.fti.b_v"};
  w.write("/fit/parameter_names", names);
  w.write("/fit/parameter_units", std::vector<std::string>{"mN mm/deg", "mN mm/deg", "mN mm/deg", "mN mm/deg",
                                                           "mN mm s/deg"});
  w.write("/fit/estimate", std::vector<double>{0.0021, 0.0034, 0.0018, 0.0029, 0.00012}, "mixed");
  w.write("/fit/standard_error", std::vector<double>{0.0001, 0.0004, 0.0002, 0.0011, 0.00003}, "mixed");
  std::vector<double> hist;
  for (int k = 0; k < 30; ++k) hist.push_back(0.8 + 250.0 * std::exp(-0.35 * k));
  w.write("/fit/cost_history", hist, "deg^2");
  const std::size_t n = names.size();
  std::vector<double> corr(n * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      corr[i * n + j] = i == j ? 1.0 : 0.9 * std::cos(1.3 * (i + j)) * std::exp(-0.3 * std::abs(double(i) - double(j)));
  w.write("/fit/correlation", corr, "1", {n, n});
  std::vector<double> finals;
  for (int s = 0; s < 20; ++s) finals.push_back(s < 7 ? 0.8 + 0.001 * s : 0.8 + 3.0 * (s - 6) * (s - 6));
  w.write("/fit/multistart/final_cost", finals, "deg^2");
  std::vector<double> t, data, model;
  for (int i = 0; i < 200; ++i) {
    double ti = i * 5.0;
    t.push_back(ti);
    model.push_back(90 + 25 * std::sin(2 * 3.141592653589793 * ti / 1000.0));
    data.push_back(model.back() + 2.0 * std::sin(12.9898 * i) * std::cos(78.233 * i));
  }
  w.write("/fit/data/time", t, "ms");
  w.write("/fit/data/middle.fti", data, "deg");
  w.write("/fit/model/middle.fti", model, "deg");
  w.commit();
}

enum class SweepShape {
  Grid,          // 4 x 4 grid over coupling strength and sign, for two start conditions (two panels)
  Scattered,     // 15 scattered (Latin-hypercube-like) points over strength and sign
  OneParameter,  // 8 strengths only
  LinkedRowsWithOptions,  // 4 rows of three coupling strengths set together x 2 gaits x 2 gates
};

// Sweep results with one failed point (index 5).
inline void write_sweep_fixture(const std::string& path, SweepShape shape = SweepShape::Grid) {
  const bool grid = shape == SweepShape::Grid;
  io::H5Writer w(path);
  w.write_run_info(fixture_info("sweep"));
  const bool linked = shape == SweepShape::LinkedRowsWithOptions;
  std::vector<std::string> names = {"coupling.strength"};
  if (shape != SweepShape::OneParameter) names.push_back("coupling.sign");
  if (grid || linked) names.push_back(grid ? "start.tripod" : "coupling.third");
  std::vector<std::string> opt_gait, opt_gate;
  w.write("/sweep/parameter_names", names);
  w.write("/sweep/parameter_units", std::vector<std::string>(names.size(), "1"));
  std::vector<double> pts;
  std::vector<double> period, ratio;
  std::vector<std::string> gait, status;
  int k = 0;
  auto add = [&](double s, double g, double start) {
    pts.push_back(s);
    if (shape != SweepShape::OneParameter) pts.push_back(g);
    if (grid || linked) pts.push_back(start);
    bool failed = k == 5;
    status.push_back(failed ? "CVODE: too much work at t = 312 ms" : "ok");
    period.push_back(failed ? std::nan("") : 900 + 300 * s - 50 * g + 20 * start);
    ratio.push_back(failed ? std::nan("") : 1.2 + 0.8 * s * g);
    gait.push_back(failed ? "failed" : (s < 0.4 ? (start > 0.5 ? "tripod" : "tetrapod") : (g > 0 ? "irregular" : "tripod")));
    ++k;
  };
  if (grid) {
    for (double start : {0.0, 1.0})
      for (double g : {-1.0, -0.5, 0.5, 1.0})
        for (double s : {0.1, 0.3, 0.6, 1.0}) add(s, g, start);
  } else if (linked) {
    for (const char* gait_opt : {"tetrapod", "tripod"})
      for (const char* gate : {"target_swing", "source_contact"})
        for (double s : {-0.6, -1.5, 0.6, 1.5}) {
          opt_gait.push_back(gait_opt);
          opt_gate.push_back(gate);
          add(std::fabs(s), s > 0 ? 1.0 : -1.0, s);  // the third column is a function of the first two
        }
  } else if (shape == SweepShape::OneParameter) {
    for (int i = 0; i < 8; ++i) add(0.05 + 0.125 * i, -1.0, 0);
  } else {
    for (int i = 0; i < 15; ++i) add(std::fmod(0.37 * i + 0.11, 1.0), std::fmod(0.61 * i + 0.05, 2.0) - 1.0, 0);
  }
  const hsize_t np = status.size();
  w.write("/sweep/points", pts, "1", {np, static_cast<hsize_t>(names.size())});
  w.write("/sweep/features/period_ms", period, "ms");
  w.write("/sweep/features/stance_swing_ratio", ratio, "1");
  w.write("/sweep/gait_class", gait);
  w.write("/sweep/status", status);
  if (linked) {
    w.write("/sweep/option_names", std::vector<std::string>{"gait", "coupling_gate"});
    w.write("/sweep/options/gait", opt_gait);
    w.write("/sweep/options/coupling_gate", opt_gate);
  }
  w.commit();
}

// A valid phasmid file with none of the groups a report draws.
inline void write_empty_fixture(const std::string& path) {
  io::H5Writer w(path);
  w.write_run_info(fixture_info("empty"));
  w.commit();
}

// Odd shapes and types everywhere: the report must list them and still render the rest.
inline void write_malformed_fixture(const std::string& path) {
  io::H5Writer w(path);
  w.write_run_info(fixture_info("malformed"));
  std::vector<double> t = {0, 1, 2, 3, 4};
  w.write("/trajectory/time", t, "ms");
  w.write("/trajectory/angles/middle/fti", std::vector<double>{1, 2, 3, 4, 5}, "deg");
  w.write("/trajectory/angles/middle/ctr", std::vector<double>{1, 2, 3}, "deg");        // wrong length
  w.write("/trajectory/angles/hind", std::vector<double>{1, 2, 3, 4, 5}, "deg");        // dataset, not a group
  w.write("/trajectory/footfall/middle", std::vector<std::string>{"a", "b"});           // strings
  w.write("/trajectory/states/x.C1.V", std::vector<double>{std::nan(""), 1, 2, 3, 4}, "mV");  // NaN -> gap
  w.write("/features/matrix", std::vector<double>(100 * 100, 1.0), "1", {100, 100});   // too big for the table
  w.write("/sensitivity/parameters", std::vector<std::string>{"a", "b"});
  w.write("/sensitivity/features/period_ms", std::vector<double>{1, 2, 3}, "ms");     // wrong length
  w.write("/sensitivity/relative/period_ms", std::vector<double>{0.5, -0.25}, "1");
  w.write("/fit/parameter_names", std::vector<std::string>{"a", "b"});
  w.write("/fit/estimate", std::vector<double>{1, 2}, "1");
  w.write("/fit/correlation", std::vector<double>{1, 0, 0}, "1");                     // not n x n
  w.write("/fit/cost_history", std::vector<double>{3, 0, -1}, "1");                   // not positive: linear axis
  w.write("/sweep/parameter_names", std::vector<std::string>{"p"});
  w.write("/sweep/points", std::vector<double>{1, 2, 3}, "1");
  w.write("/sweep/gait_class", std::vector<std::string>{"tripod"});                   // wrong length
  w.write_scalar("/lonely_scalar", 1.0, "1");
  w.commit();
}

}  // namespace phasmid::testing
