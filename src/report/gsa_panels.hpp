#pragma once
// The /gsa group of a `phasmid gsa` file (docs/gsa.md) as report JSON: per feature the indices
// with their interval half-widths, the failed-output counts and the convergence of nested
// subsets, as the analysis stored them (read with gsa::read_gsa_h5; nothing is recomputed).
// reports/report.js draws them (docs/reports.md, "Global sensitivity analysis").
#include <nlohmann/json.hpp>

#include "io/h5_file.hpp"

namespace phasmid::report {

nlohmann::json extract_gsa(const io::H5Reader& r);

}  // namespace phasmid::report
