#include "report/panels.hpp"

#include "io/h5_file.hpp"
#include "io/h5_scalar.hpp"
#include "report/panel_common.hpp"

namespace phasmid::report {

using nlohmann::json;
using io::H5Reader;

void extract_parameters(const H5Reader& r, json& out) {
  auto names = strings_or_empty(r, "/parameters/names");
  if (names.empty() || !is_numeric_dataset(r, "/parameters/values")) {
    note_ignored(out, "/parameters");
    return;
  }
  auto values = r.read_doubles("/parameters/values");
  auto units = strings_or_empty(r, "/parameters/units");
  json rows = json::array();
  for (std::size_t i = 0; i < names.size() && i < values.size(); ++i)
    rows.push_back({{"name", names[i]}, {"value", num(values[i])}, {"units", i < units.size() ? units[i] : ""}});
  out["parameters"] = rows;
}

void extract_features(const H5Reader& r, json& out) {
  std::vector<std::string> names;
  walk(r, "/features", "", names);
  json rows = json::array();
  for (const auto& name : names) {
    std::string p = "/features/" + name;
    if (is_numeric_dataset(r, p) && n_elements(r.dims(p)) == 1) {
      rows.push_back({{"name", name}, {"value", num(io::read_scalar(r, p))}, {"units", units_of(r, p)}});
    } else if (is_numeric_dataset(r, p) && n_elements(r.dims(p)) <= 64) {  // e.g. phases of six legs
      rows.push_back({{"name", name}, {"value", nums(r.read_doubles(p))}, {"units", units_of(r, p)}});
    } else if (is_dataset(r, p) && is_string_dataset(r, p)) {
      rows.push_back({{"name", name}, {"value", r.read_strings(p)}, {"units", ""}});
    } else {
      note_ignored(out, p);
    }
  }
  out["features"] = rows;
}

}  // namespace phasmid::report
