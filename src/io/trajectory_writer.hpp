#pragma once
// Writes a simulated trajectory and the resolved parameters in the layout of docs/hdf5.md.
#include "io/h5_file.hpp"
#include "model/ode_model.hpp"
#include "solver/simulator.hpp"

namespace phasmid::io {

// /trajectory/time (ms), /trajectory/angles/<leg>/<joint> (deg), /trajectory/states/<name>.
void write_trajectory(H5Writer& w, const model::OdeModel& m, const solver::SolveResult& r);
// /parameters/names, /parameters/values, /parameters/units, /parameters/sources.
void write_parameters(H5Writer& w, const model::OdeModel& m, const std::vector<double>& p);
void write_parameters(H5Writer& w, const model::ParameterSet& parameters, const std::vector<double>& p);

}  // namespace phasmid::io
