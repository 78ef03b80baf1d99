#include "io/trajectory_writer.hpp"

#include <cmath>

namespace phasmid::io {

void write_trajectory(H5Writer& w, const model::OdeModel& m, const solver::SolveResult& r) {
  w.write("/trajectory/time", r.t, "ms");
  const size_t n_out = r.t.size();
  std::vector<double> col(n_out);
  for (const auto& a : m.angles()) {
    for (size_t k = 0; k < n_out; ++k) col[k] = r.state(k, a.angle_state) * 180.0 / M_PI;
    w.write("/trajectory/angles/" + a.leg + "/" + a.joint, col, "deg");
    for (size_t k = 0; k < n_out; ++k) col[k] = r.state(k, a.velocity_state) * 180.0 / M_PI;
    w.write("/trajectory/angular_velocity/" + a.leg + "/" + a.joint, col, "deg/s");
  }
  // Footfall pattern of walking models: 1 swing, 0 stance (ground contact: beta below the
  // leg's `<leg>.coupling.beta_thr_pr`, docs/walking_model.md).
  for (const auto& a : m.angles()) {
    const std::string thr = a.leg + ".coupling.beta_thr_pr";
    if (a.joint != "ctr" || !m.parameters().contains(thr)) continue;
    const double thr_rad = m.parameters().value(thr) * M_PI / 180.0;
    for (size_t k = 0; k < n_out; ++k) col[k] = r.state(k, a.angle_state) < thr_rad ? 0.0 : 1.0;
    w.write("/trajectory/footfall/" + a.leg, col, "1");
  }
  for (size_t i = 0; i < m.num_states(); ++i) {
    for (size_t k = 0; k < n_out; ++k) col[k] = r.state(k, i);
    w.write("/trajectory/states/" + m.states()[i].name, col, m.states()[i].unit);
  }
  w.set_attribute("/trajectory", "solver_steps", static_cast<double>(r.stats.steps));
  w.set_attribute("/trajectory", "wall_seconds", r.stats.wall_seconds);
}

void write_parameters(H5Writer& w, const model::OdeModel& m, const std::vector<double>& p) {
  std::vector<std::string> units, sources;
  for (auto& q : m.parameters().all()) {
    units.push_back(q.unit);
    sources.push_back(q.source);
  }
  w.write("/parameters/names", m.parameters().names());
  w.write("/parameters/values", p, "see /parameters/units");
  w.write("/parameters/units", units);
  w.write("/parameters/sources", sources);
}

}  // namespace phasmid::io
