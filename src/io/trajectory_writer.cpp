#include "io/trajectory_writer.hpp"

#include "common/units.hpp"
#include "model/body_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace phasmid::io {

void write_trajectory(H5Writer& w, const model::OdeModel& m, const solver::SolveResult& r) {
  w.write("/trajectory/time", r.t, "ms");
  const size_t n_out = r.t.size();
  std::vector<double> col(n_out);
  for (const auto& a : m.angles()) {
    for (size_t k = 0; k < n_out; ++k) col[k] = units::rad_to_deg(r.state(k, a.angle_state));
    w.write("/trajectory/angles/" + a.leg + "/" + a.joint, col, "deg");
    for (size_t k = 0; k < n_out; ++k) col[k] = units::rad_to_deg(r.state(k, a.velocity_state));
    w.write("/trajectory/angular_velocity/" + a.leg + "/" + a.joint, col, "deg/s");
  }
  // Footfall pattern of walking models: 1 swing, 0 stance (ground contact: beta below the
  // leg's `<leg>.coupling.beta_thr_pr`, docs/walking_model.md).
  for (const auto& a : m.angles()) {
    const std::string thr = a.leg + ".coupling.beta_thr_pr";
    if (a.joint != "ctr" || !m.parameters().contains(thr)) continue;
    const double thr_rad = units::deg_to_rad(m.parameters().value(thr));
    for (size_t k = 0; k < n_out; ++k) col[k] = r.state(k, a.angle_state) < thr_rad ? 0.0 : 1.0;
    w.write("/trajectory/footfall/" + a.leg, col, "1");
  }
  // Six-leg pattern of the three-leg model (Section 2.5.4): the left side L1-L3 is the
  // simulated front, middle, hind leg; the right side R1-R3 the same pattern delayed by
  // contralateral.lag * gait.period_ms (linear interpolation; the first value before that).
  if (m.parameters().contains("contralateral.lag") && m.parameters().contains("gait.period_ms")) {
    const double shift = m.parameters().value("contralateral.lag") * m.parameters().value("gait.period_ms");
    auto delayed = [&](const std::vector<double>& x) {
      std::vector<double> y(n_out);
      for (size_t k = 0; k < n_out; ++k) {
        double t = r.t[k] - shift;
        if (t <= r.t.front()) { y[k] = x.front(); continue; }
        size_t j = std::upper_bound(r.t.begin(), r.t.end(), t) - r.t.begin();
        double w = (t - r.t[j - 1]) / (r.t[j] - r.t[j - 1]);
        y[k] = (1 - w) * x[j - 1] + w * x[j];
      }
      return y;
    };
    const std::map<std::string, std::string> side = {{"front", "1"}, {"middle", "2"}, {"hind", "3"}};
    for (const auto& a : m.angles()) {
      auto it = side.find(a.leg);
      if (it == side.end()) continue;
      std::vector<double> x(n_out);
      for (size_t k = 0; k < n_out; ++k) x[k] = units::rad_to_deg(r.state(k, a.angle_state));
      w.write("/trajectory/angles/L" + it->second + "/" + a.joint, x, "deg");
      w.write("/trajectory/angles/R" + it->second + "/" + a.joint, delayed(x), "deg");
      const std::string thr = a.leg + ".coupling.beta_thr_pr";
      if (a.joint == "ctr" && m.parameters().contains(thr)) {
        for (auto& v : x) v = v < m.parameters().value(thr) ? 0.0 : 1.0;
        w.write("/trajectory/footfall/L" + it->second, x, "1");
        auto d = delayed(x);
        for (auto& v : d) v = v < 0.5 ? 0.0 : 1.0;
        w.write("/trajectory/footfall/R" + it->second, d, "1");
      }
    }
  }
  // Curve walking (Section 3.2.3): body path from the two middle legs, docs/walking_model.md.
  if (m.parameters().contains("body.reach_mm") && m.parameters().contains("L2.coupling.beta_thr_pr")) {
    std::map<std::string, std::vector<double>> a;
    for (const auto& ch : m.angles()) {
      if (ch.leg != "L2" && ch.leg != "R2") continue;
      std::vector<double> x(n_out);
      for (size_t k = 0; k < n_out; ++k) x[k] = units::rad_to_deg(r.state(k, ch.angle_state));
      a[ch.leg + "." + ch.joint] = x;
    }
    model::BodyPath bp = model::integrate_body_path(
        r.t, a["L2.thc"], a["L2.ctr"], a["R2.thc"], a["R2.ctr"], m.parameters().value("L2.coupling.beta_thr_pr"),
        m.parameters().value("body.reach_mm"), m.parameters().value("body.half_width_mm"));
    w.write("/body/x", bp.x_mm, "mm");
    w.write("/body/y", bp.y_mm, "mm");
    w.write("/body/heading", bp.heading_deg, "deg");
  }
  for (size_t i = 0; i < m.num_states(); ++i) {
    for (size_t k = 0; k < n_out; ++k) col[k] = r.state(k, i);
    w.write("/trajectory/states/" + m.states()[i].name, col, m.states()[i].unit);
  }
  w.set_attribute("/trajectory", "solver_steps", static_cast<double>(r.stats.steps));
  w.set_attribute("/trajectory", "wall_seconds", r.stats.wall_seconds);
  w.set_attribute("/trajectory", "integrators", static_cast<double>(r.stats.integrators));
}

void write_parameters(H5Writer& w, const model::OdeModel& m, const std::vector<double>& p) {
  write_parameters(w, m.parameters(), p);
}

void write_parameters(H5Writer& w, const model::ParameterSet& ps, const std::vector<double>& p) {
  std::vector<std::string> units, sources;
  for (auto& q : ps.all()) {
    units.push_back(q.unit);
    sources.push_back(q.source);
  }
  w.write("/parameters/names", ps.names());
  w.write("/parameters/values", p, "see /parameters/units");
  w.write("/parameters/units", units);
  w.write("/parameters/sources", sources);
}

}  // namespace phasmid::io
