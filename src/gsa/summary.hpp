#pragma once
// The table `phasmid gsa` (and phasmid.gsa()) prints: per feature the used and dropped counts
// and each parameter's indices with their interval half-widths.
#include <string>

#include "gsa/gsa_h5.hpp"

namespace phasmid::gsa {

std::string gsa_summary(const GsaResult& r);

}  // namespace phasmid::gsa
