#pragma once
// Features of a model's catalogue that a run could not compute (too few turning points or
// steps after discard_ms: a short run, or a joint that does not oscillate) are reported, not
// left out: NaN in /features with the reason as the dataset's `not_computed` attribute, and a
// note on the terminal (docs/features.md).
#include <string>
#include <vector>

#include "features/features.hpp"
#include "io/h5_file.hpp"

namespace phasmid::features {

inline constexpr const char* kNotComputedReason =
    "too few cycles after discard_ms (a short run, or a joint or leg that does not oscillate)";

// Appends every catalogue feature absent from `features` as NaN; returns their names.
std::vector<std::string> add_missing_features(std::vector<Feature>& features, const std::vector<FeatureInfo>& catalogue);
// Sets /features/<name>.not_computed = kNotComputedReason for each name (after write_features_h5).
void mark_missing_features_h5(io::H5Writer& out, const std::vector<std::string>& names);
// "2 features not computed (NaN): a, b: <reason>", or "" when none is missing.
std::string missing_features_note(const std::vector<std::string>& names);

}  // namespace phasmid::features
