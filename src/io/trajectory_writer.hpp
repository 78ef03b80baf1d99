#pragma once
// Writes a simulated trajectory and the resolved parameters in the layout of docs/hdf5.md.
#include "io/h5_file.hpp"
#include "model/ode_model.hpp"
#include "solver/simulator.hpp"

namespace phasmid::io {

// /trajectory/time (ms), /trajectory/angles/<leg>/<joint> (deg), /trajectory/states/<name>.
// Datasets chunked and extendible as io::TrajectoryStream writes them (the same file whether the
// run streamed its samples or kept them).
void write_trajectory(H5Writer& w, const model::OdeModel& m, const solver::SolveResult& r);
// The attributes solver_steps, wall_seconds, integrators of /trajectory (write_trajectory
// writes them; a streamed run after TrajectoryStream::finish).
void write_solver_stats(H5Writer& w, const solver::SolverStats& stats);
// /parameters/names, /parameters/values, /parameters/units, /parameters/sources.
void write_parameters(H5Writer& w, const model::OdeModel& m, const std::vector<double>& p);
void write_parameters(H5Writer& w, const model::ParameterSet& parameters, const std::vector<double>& p);

}  // namespace phasmid::io
