#pragma once
// /continuation in HDF5 (docs/continuation.md, docs/hdf5.md): one row per branch point.
#include "continuation/continuation.hpp"

namespace phasmid::io {
class H5Writer;
}

namespace phasmid::continuation {

// /continuation/{parameter, period_ms, amplitude, stable, newton_iterations, residual,
// multipliers_real, multipliers_imag, multipliers_abs (N x Ns, by decreasing modulus),
// trivial_multiplier, state_names, state_on_section (N x Ns), features/<name>,
// special_points/{index, kind, parameter, period_ms, note}}; attributes parameter,
// parameter_unit, end, shots, seconds.
void write_branch_h5(io::H5Writer& out, const model::OdeModel& model, const Branch& branch);

// One line per special point and a closing line: what the branch found.
std::string format_summary(const Branch& branch);

}  // namespace phasmid::continuation
