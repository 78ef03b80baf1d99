#include "features/missing_features.hpp"

#include <limits>
#include <set>

namespace phasmid::features {

std::vector<std::string> add_missing_features(std::vector<Feature>& features, const std::vector<FeatureInfo>& catalogue) {
  std::set<std::string> have;
  for (const auto& f : features) have.insert(f.name);
  std::vector<std::string> missing;
  for (const auto& info : catalogue) {
    if (have.count(info.name)) continue;
    features.push_back({info.name, std::numeric_limits<double>::quiet_NaN(), info.unit});
    missing.push_back(info.name);
  }
  return missing;
}

void mark_missing_features_h5(io::H5Writer& out, const std::vector<std::string>& names) {
  for (const auto& n : names) out.set_attribute("/features/" + n, "not_computed", kNotComputedReason);
}

std::string missing_features_note(const std::vector<std::string>& names) {
  if (names.empty()) return "";
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  return std::to_string(names.size()) + " feature" + (names.size() == 1 ? "" : "s") + " not computed (NaN): " + list +
         ": " + kNotComputedReason;
}

}  // namespace phasmid::features
