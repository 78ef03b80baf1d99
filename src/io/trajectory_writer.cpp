#include "io/trajectory_writer.hpp"

#include "io/trajectory_stream.hpp"

namespace phasmid::io {

void write_trajectory(H5Writer& w, const model::OdeModel& m, const solver::SolveResult& r) {
  TrajectoryStream stream(w, m);
  for (size_t k = 0; k < r.t.size(); ++k) stream.record(r.t[k], &r.y[k * r.n_states], r.n_states);
  stream.finish();
  write_solver_stats(w, r.stats);
}

void write_solver_stats(H5Writer& w, const solver::SolverStats& stats) {
  w.set_attribute("/trajectory", "solver_steps", static_cast<double>(stats.steps));
  w.set_attribute("/trajectory", "wall_seconds", stats.wall_seconds);
  w.set_attribute("/trajectory", "cpu_seconds", stats.cpu_seconds);
  w.set_attribute("/trajectory", "integrators", static_cast<double>(stats.integrators));
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
