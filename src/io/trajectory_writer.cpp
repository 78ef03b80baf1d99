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
  // leg's threshold, docs/walking_model.md).
  auto threshold_deg = [&](const model::ContactLeg& l) { return m.parameters().at(l.threshold_param).value; };
  for (const model::ContactLeg& l : m.structure().contact_legs) {
    const double thr_rad = units::deg_to_rad(threshold_deg(l));
    for (size_t k = 0; k < n_out; ++k) col[k] = r.state(k, l.beta_state) < thr_rad ? 0.0 : 1.0;
    w.write("/trajectory/footfall/" + l.leg, col, "1");
  }
  // Six-leg pattern of the three-leg model (Section 2.5.4): the left side L1-L3 is the
  // simulated front, middle, hind leg; the right side R1-R3 the same pattern delayed by
  // the declared lag * period (linear interpolation; the first value before that).
  if (const auto& copy = m.structure().contralateral) {
    const double shift = m.parameters().at(copy->lag_param).value * m.parameters().at(copy->period_param).value;
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
      const model::ContactLeg* contact = m.contact_leg(a.leg);
      if (a.joint == "ctr" && contact) {
        for (auto& v : x) v = v < threshold_deg(*contact) ? 0.0 : 1.0;
        w.write("/trajectory/footfall/L" + it->second, x, "1");
        auto d = delayed(x);
        for (auto& v : d) v = v < 0.5 ? 0.0 : 1.0;
        w.write("/trajectory/footfall/R" + it->second, d, "1");
      }
    }
  }
  // Curve walking (Section 3.2.3): body path from the two middle legs, docs/walking_model.md.
  const model::ContactLeg* body_left = m.structure().body ? m.contact_leg(m.structure().body->left_leg) : nullptr;
  if (body_left) {
    const model::BodyGeometry& body = *m.structure().body;
    std::map<std::string, std::vector<double>> a;
    for (const auto& ch : m.angles()) {
      if (ch.leg != body.left_leg && ch.leg != body.right_leg) continue;
      std::vector<double> x(n_out);
      for (size_t k = 0; k < n_out; ++k) x[k] = units::rad_to_deg(r.state(k, ch.angle_state));
      a[ch.leg + "." + ch.joint] = x;
    }
    const std::string L = body.left_leg + ".", R = body.right_leg + ".";
    model::BodyPath bp = model::integrate_body_path(
        r.t, a[L + "thc"], a[L + "ctr"], a[R + "thc"], a[R + "ctr"], threshold_deg(*body_left),
        m.parameters().at(body.reach_param).value, m.parameters().at(body.half_width_param).value);
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
