#include "report/panels.hpp"

#include <algorithm>
#include <set>

#include "common/error.hpp"
#include "io/h5_file.hpp"
#include "report/panel_common.hpp"
#include "sweep/ranges.hpp"

namespace phasmid::report {
namespace {

using nlohmann::json;
using io::H5Reader;

// The range analysis of a one-at-a-time sweep (docs/sweep.md, "Ranges"), read by the sweep code's
// own reader; each parameter's unit comes from /sweep/parameter_units.
json extract_ranges(const H5Reader& r, const std::vector<std::string>& names, const json& units) {
  json params = json::array();
  for (const sweep::ParameterRange& p : sweep::read_ranges_h5(r)) {
    const auto at = std::find(names.begin(), names.end(), p.parameter);
    const std::size_t k = static_cast<std::size_t>(at - names.begin());
    params.push_back({{"name", p.parameter}, {"units", k < units.size() ? units[k] : json("")},
                      {"values", nums(p.values)}, {"in_range", p.in_range}, {"lower", num(p.lower)},
                      {"upper", num(p.upper)}, {"contiguous", p.contiguous}});
  }
  return {{"feature", r.read_string_attribute("/sweep/ranges", "feature")}, {"parameters", params}};
}

// /sweep/points as rows of one value per parameter; n_points is left 0 when there are none or
// their shape does not match the names.
json points(const H5Reader& r, json& out, std::size_t n_params, std::size_t& n_points) {
  json rows = json::array();
  n_points = 0;
  if (!is_numeric_dataset(r, "/sweep/points") || n_params == 0) return rows;
  auto d = r.dims("/sweep/points");
  auto v = r.read_doubles("/sweep/points");
  if (n_elements(d) % n_params != 0) {
    note_ignored(out, "/sweep/points (shape does not match parameter_names)");
    return rows;
  }
  n_points = n_elements(d) / n_params;
  for (std::size_t i = 0; i < n_points; ++i) {
    json row = json::array();
    for (std::size_t j = 0; j < n_params; ++j) row.push_back(num(v[i * n_params + j]));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

void extract_sweep(const H5Reader& r, json& out) {
  json s = json::object();
  auto names = strings_or_empty(r, "/sweep/parameter_names");
  s["parameter_names"] = names;
  s["parameter_units"] = strings_or_empty(r, "/sweep/parameter_units");
  std::size_t n_points = 0;
  s["points"] = points(r, out, names.size(), n_points);
  s["features"] = named_vectors(r, out, "/sweep/features", n_points);
  auto gait = strings_or_empty(r, "/sweep/gait_class");
  auto status = strings_or_empty(r, "/sweep/status");
  if (gait.size() == n_points)
    s["gait_class"] = gait;
  else if (r.exists("/sweep/gait_class"))
    note_ignored(out, "/sweep/gait_class (not one per point)");
  if (status.size() == n_points)
    s["status"] = status;
  else if (r.exists("/sweep/status"))
    note_ignored(out, "/sweep/status (not one per point)");
  // Swept [model] options (strings per point): the report draws one panel per combination.
  s["options"] = json::array();
  for (const auto& name : strings_or_empty(r, "/sweep/option_names")) {
    auto v = strings_or_empty(r, "/sweep/options/" + name);
    if (v.size() == n_points) s["options"].push_back({{"name", name}, {"values", v}});
    else note_ignored(out, "/sweep/options/" + name + " (not one per point)");
  }
  try {
    s["design"] = r.read_string_attribute("/sweep", "design");
  } catch (const Error&) {
    s["design"] = "";
  }
  if (r.exists("/sweep/ranges")) {
    try {
      s["ranges"] = extract_ranges(r, names, s["parameter_units"]);
    } catch (const Error& e) {
      note_ignored(out, std::string("/sweep/ranges (unreadable: ") + e.what() + ")");
    }
  }
  for (const auto& c : r.children("/sweep")) {
    static const std::set<std::string> known = {"parameter_names", "parameter_units", "points", "features",
                                                "gait_class", "status", "option_names", "options", "ranges"};
    if (!known.count(c)) note_ignored(out, "/sweep/" + c);
  }
  out["sweep"] = s;
}

}  // namespace phasmid::report
