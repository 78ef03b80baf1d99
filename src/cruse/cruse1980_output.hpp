#pragma once
// HDF5 output of Cruse (1980) runs (layout in docs/cruse1980.md).
#include <string>

#include "cruse/cruse1980_features.hpp"

namespace phasmid {
namespace io {
class H5Writer;
}

namespace cruse {

// /trajectory, /events, /parameters and /features of one run (no root attributes).
void write_run_contents(io::H5Writer& w, const Parameters& p, const Trajectory& run, const Features& f);

}  // namespace cruse
}  // namespace phasmid
