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

// /fit/steps/<i>: the recording's mean and SD per phase bin against the model's profile, per
// observable, with the periods and duty factors (docs/recordings.md).
json step_cycles(const H5Reader& r, json& out) {
  json arr = json::array();
  for (const auto& i : r.children("/fit/steps")) {
    const std::string g = "/fit/steps/" + i;
    if (!is_numeric_dataset(r, g + "/phase") || !r.is_group(g + "/data_mean")) {
      note_ignored(out, g);
      continue;
    }
    const std::vector<double> phase = r.read_doubles(g + "/phase");
    json s;
    s["phase"] = nums(phase);
    for (const char* a : {"leg", "model_leg", "file", "condition"})
      s[a] = r.has_attribute(g, a) ? json(r.read_string_attribute(g, a)) : json(nullptr);
    for (const char* a : {"data_period_ms", "model_period_ms", "data_duty_factor", "model_duty_factor", "data_steps", "model_steps",
                          "period_sigma_ms", "duty_factor_sigma"})
      s[a] = r.has_attribute(g, a) ? json(r.read_double_attribute(g, a)) : json(nullptr);
    s["channels"] = json::array();
    for (const auto& c : r.children(g + "/data_mean")) {
      json ch{{"name", c}};
      bool ok = true;
      for (const char* part : {"data_mean", "data_sd", "model"}) {
        const std::string p = g + "/" + part + "/" + c;
        ok = ok && is_numeric_dataset(r, p) && n_elements(r.dims(p)) == phase.size();
        if (ok) ch[part] = nums(r.read_doubles(p));
      }
      if (ok) s["channels"].push_back(ch);
      else note_ignored(out, g + "/.../" + c);
    }
    arr.push_back(s);
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
  f["step_cycles"] = r.is_group("/fit/steps") ? step_cycles(r, out) : json::array();
  out["fit"] = f;
}

}  // namespace phasmid::report
