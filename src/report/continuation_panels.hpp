#pragma once
// The /continuation group of a `phasmid continue` file for the report (docs/continuation.md):
// parameter, period, tracked features, stability, multipliers and special points as JSON.
#include <nlohmann/json.hpp>

namespace phasmid::io {
class H5Reader;
}

namespace phasmid::report {

// Fills out["continuation"]; throws Error if the group's datasets are inconsistent.
void extract_continuation(const io::H5Reader& r, nlohmann::json& out);

}  // namespace phasmid::report
