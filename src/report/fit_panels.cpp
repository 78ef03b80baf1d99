#include "report/panels.hpp"

#include "io/h5_file.hpp"
#include "report/panel_common.hpp"

namespace phasmid::report {
namespace {

using nlohmann::json;
using io::H5Reader;

// /fit/data/<column> against /fit/model/<column>, each with its times.
json kinematics(const H5Reader& r, json& out, const std::vector<double>& t, std::size_t max_points) {
  json arr = json::array();
  for (const auto& c : r.children("/fit/data")) {
    if (c == "time") continue;
    std::string dp = "/fit/data/" + c, mp = "/fit/model/" + c;
    if (!is_numeric_dataset(r, dp) || n_elements(r.dims(dp)) != t.size()) {
      note_ignored(out, dp);
      continue;
    }
    json k;
    k["name"] = c;
    k["units"] = units_of(r, dp);
    json d = series(t, r.read_doubles(dp), max_points);
    if (!d.contains("t")) d["t"] = nums(t);
    k["data"] = d;
    if (is_numeric_dataset(r, mp) && n_elements(r.dims(mp)) == t.size()) {
      json m = series(t, r.read_doubles(mp), max_points);
      if (!m.contains("t")) m["t"] = nums(t);
      k["model"] = m;
    }
    arr.push_back(k);
  }
  return arr;
}

}  // namespace

void extract_fit(const H5Reader& r, json& out, std::size_t max_points) {
  json f = json::object();
  auto names = strings_or_empty(r, "/fit/parameter_names");
  f["parameter_names"] = names;
  auto vec = [&](const std::string& p) -> json {
    return is_numeric_dataset(r, p) ? nums(r.read_doubles(p)) : json(nullptr);
  };
  f["parameter_units"] = strings_or_empty(r, "/fit/parameter_units");
  f["estimate"] = vec("/fit/estimate");
  f["standard_error"] = vec("/fit/standard_error");
  f["cost_history"] = vec("/fit/cost_history");
  f["cost_units"] = units_of(r, "/fit/cost_history");
  if (is_numeric_dataset(r, "/fit/correlation")) {
    if (n_elements(r.dims("/fit/correlation")) == names.size() * names.size())
      f["correlation"] = vec("/fit/correlation");
    else
      note_ignored(out, "/fit/correlation (not n x n for the n parameter_names)");
  }
  f["final_cost"] = vec("/fit/multistart/final_cost");
  f["kinematics"] = json::array();
  if (is_numeric_dataset(r, "/fit/data/time")) {
    auto t = r.read_doubles("/fit/data/time");
    f["time_units"] = units_of(r, "/fit/data/time");
    f["kinematics"] = kinematics(r, out, t, max_points);
  }
  out["fit"] = f;
}

}  // namespace phasmid::report
