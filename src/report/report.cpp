#include "report/report.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <unistd.h>

#include "common/embedded.hpp"
#include "common/error.hpp"
#include "io/h5_file.hpp"
#include "io/h5_scalar.hpp"
#include "io/output_lock.hpp"
#include "io/output_path.hpp"
#include "report/continuation_panels.hpp"
#include "io/h5_stream.hpp"
#include "sweep/ranges.hpp"
#include "report/gsa_panels.hpp"

namespace phasmid::report {
namespace {

using nlohmann::json;
using io::H5Reader;

// 6 significant digits is plenty for a page and keeps the inlined JSON small.
json num(double v) {
  if (!std::isfinite(v)) return nullptr;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return std::strtod(buf, nullptr);
}

json nums(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) a.push_back(num(x));
  return a;
}

std::string units_of(const H5Reader& r, const std::string& path) {
  try {
    return r.read_string_attribute(path, "units");
  } catch (const Error&) {
    return "";
  }
}

std::string root_attr(const H5Reader& r, const std::string& name) {
  try {
    return r.read_string_attribute("/", name);
  } catch (const Error&) {
    return "";
  }
}

bool is_dataset(const H5Reader& r, const std::string& path) { return r.exists(path) && !r.is_group(path); }

bool is_string_dataset(const H5Reader& r, const std::string& path) {
  hid_t ds = H5Dopen2(r.id(), path.c_str(), H5P_DEFAULT);
  if (ds < 0) return false;
  hid_t type = H5Dget_type(ds);
  bool s = H5Tget_class(type) == H5T_STRING;
  H5Tclose(type);
  H5Dclose(ds);
  return s;
}

bool is_numeric_dataset(const H5Reader& r, const std::string& path) {
  if (!is_dataset(r, path)) return false;
  hid_t ds = H5Dopen2(r.id(), path.c_str(), H5P_DEFAULT);
  if (ds < 0) return false;
  hid_t type = H5Dget_type(ds);
  auto c = H5Tget_class(type);
  H5Tclose(type);
  H5Dclose(ds);
  return c == H5T_FLOAT || c == H5T_INTEGER;
}

std::size_t count(const std::vector<hsize_t>& d) {
  std::size_t n = 1;
  for (auto x : d) n *= static_cast<std::size_t>(x);
  return n;
}

std::vector<std::string> strings_or_empty(const H5Reader& r, const std::string& path) {
  if (!is_dataset(r, path) || !is_string_dataset(r, path)) return {};
  return r.read_strings(path);
}

// Every dataset below `group`, as paths relative to it ("a/b"), in name order. phasmid nests
// its groups at most four deep; a damaged file can link a group into itself, so the walk is
// bounded in depth and in the number of datasets instead of following the cycle for ever.
void walk(const H5Reader& r, const std::string& group, const std::string& prefix, std::vector<std::string>& out,
          int depth = 0) {
  constexpr int kMaxDepth = 16;
  constexpr std::size_t kMaxDatasets = 1000000;
  if (depth > kMaxDepth)
    throw Error(r.path() + ": groups nested more than " + std::to_string(kMaxDepth) + " deep at " + group +
                " (a damaged file: a group linked into itself?)");
  for (const auto& c : r.children(group)) {
    std::string full = group == "/" ? "/" + c : group + "/" + c;
    std::string rel = prefix.empty() ? c : prefix + "/" + c;
    if (r.is_group(full))
      walk(r, full, rel, out, depth + 1);
    else
      out.push_back(rel);
    if (out.size() > kMaxDatasets)
      throw Error(r.path() + ": more than " + std::to_string(kMaxDatasets) + " datasets below " + group);
  }
}

int rank_of(const std::string& name, const std::vector<std::string>& order) {
  auto it = std::find(order.begin(), order.end(), name);
  return it == order.end() ? static_cast<int>(order.size()) : static_cast<int>(it - order.begin());
}
const std::vector<std::string> kLegOrder = {"front", "middle", "hind", "L1", "L2", "L3", "R1", "R2", "R3"};
const std::vector<std::string> kJointOrder = {"thc", "ctr", "fti"};

void sort_by(std::vector<std::string>& names, const std::vector<std::string>& order) {
  std::stable_sort(names.begin(), names.end(), [&](const std::string& a, const std::string& b) {
    int ra = rank_of(a, order), rb = rank_of(b, order);
    return ra != rb ? ra < rb : a < b;
  });
}

// A time series for the page: y values, plus its own t when it had to be decimated.
json series(const std::vector<double>& t, const std::vector<double>& y, std::size_t max_points) {
  json s;
  if (y.size() <= max_points) {
    s["y"] = nums(y);
    return s;
  }
  auto idx = decimate_indices(y, max_points);
  std::vector<double> tt, yy;
  for (auto i : idx) {
    tt.push_back(i < t.size() ? t[i] : static_cast<double>(i));
    yy.push_back(y[i]);
  }
  s["t"] = nums(tt);
  s["y"] = nums(yy);
  return s;
}

json intervals_json(const std::vector<double>& t, const std::vector<double>& flag) {
  json a = json::array();
  for (auto& [a0, a1] : intervals_where(t, flag)) a.push_back({num(a0), num(a1)});
  return a;
}

void note_ignored(json& out, const std::string& path) { out["ignored"].push_back(path); }

// ---------------------------------------------------------------- trajectory
// "<leg>.<joint>.<unit>.V": is <unit> a CPG unit (C, C1, cpg_ext, ...) or a motor neuron (MN1, mn_flx)?
bool is_cpg_or_mn(const std::string& name) {
  const std::string stem = name.substr(0, name.size() - 2);
  const auto dot = stem.rfind('.');
  const std::string unit = dot == std::string::npos ? stem : stem.substr(dot + 1);
  auto lower = unit;
  for (auto& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower.rfind("cpg", 0) == 0 || lower.rfind("mn", 0) == 0) return true;
  if (!unit.empty() && unit[0] == 'C') {  // C, C1, C2, C_ext
    return unit.size() == 1 || std::isdigit(static_cast<unsigned char>(unit[1])) || unit[1] == '_';
  }
  return false;
}

// Samples of a trajectory series the report reads at most (8 MiB of doubles), before decimating
// to what a plot shows.
constexpr std::size_t kMaxReadSamples = std::size_t{1} << 20;

void extract_trajectory(const H5Reader& r, json& out, std::size_t max_points) {
  json tr = json::object();
  if (!is_numeric_dataset(r, "/trajectory/time")) {
    note_ignored(out, "/trajectory (no /trajectory/time)");
    return;
  }
  // A trajectory longer than kMaxReadSamples is read every stride-th sample (by hyperslab),
  // so that what the report allocates per series is bounded whatever the file declares.
  const std::vector<hsize_t> time_dims = r.dims("/trajectory/time");
  const std::size_t n = count(time_dims);  // samples in the file
  const hsize_t stride = time_dims.size() == 1 && n > kMaxReadSamples ? (n + kMaxReadSamples - 1) / kMaxReadSamples : 1;
  auto read = [&](const std::string& path) {
    return stride == 1 ? r.read_doubles(path) : io::read_strided(r, path, stride);
  };
  const auto t = read("/trajectory/time");
  const std::size_t m = t.size();  // samples read
  tr["time_units"] = units_of(r, "/trajectory/time");
  tr["t_range"] = {num(t.empty() ? 0 : t.front()), num(t.empty() ? 0 : t.back())};
  tr["decimated"] = m > max_points || stride > 1;
  if (m <= max_points && stride == 1) tr["time"] = nums(t);

  auto series_ok = [&](const std::string& path) {
    return is_numeric_dataset(r, path) && !r.dims(path).empty() && r.dims(path)[0] == n;
  };

  for (const char* kind : {"angles", "angular_velocity"}) {
  const std::string group = std::string("/trajectory/") + kind;
  tr[kind] = json::array();
  if (r.is_group(group)) {
    auto legs = r.children(group);
    sort_by(legs, kLegOrder);
    for (const auto& leg : legs) {
      std::string lp = group + "/" + leg;
      if (!r.is_group(lp)) {
        note_ignored(out, lp);
        continue;
      }
      auto joints = r.children(lp);
      sort_by(joints, kJointOrder);
      for (const auto& joint : joints) {
        std::string p = lp + "/" + joint;
        if (!series_ok(p) || count(r.dims(p)) != n) {
          note_ignored(out, p);
          continue;
        }
        json s = series(t, read(p), max_points);
        s["leg"] = leg;
        s["joint"] = joint;
        s["units"] = units_of(r, p);
        tr[kind].push_back(s);
      }
    }
  }
  }

  // States: membrane potentials (<...>.<unit>.V) are drawn, CPG and motor-neuron units (C1, cpg_ext,
  // MN2, mn_flx, ...) apart from the other neurons (interneurons, sensory units); the rest is listed.
  tr["voltages"] = json::array();
  tr["other_states"] = json::array();
  if (r.is_group("/trajectory/states")) {
    std::vector<std::string> names;
    walk(r, "/trajectory/states", "", names);
    for (const auto& name : names) {
      std::string p = "/trajectory/states/" + name;
      const bool is_voltage = name.size() > 2 && name.compare(name.size() - 2, 2, ".V") == 0;
      if (is_voltage && series_ok(p) && count(r.dims(p)) == n) {
        json s = series(t, read(p), max_points);
        s["name"] = name;
        s["kind"] = is_cpg_or_mn(name) ? "cpg_mn" : "other";
        s["units"] = units_of(r, p);
        tr["voltages"].push_back(s);
      } else {
        tr["other_states"].push_back({{"name", name}, {"units", units_of(r, p)}});
      }
    }
  }

  auto legs_in = [&](const std::string& group) {
    std::vector<std::string> legs;
    if (r.is_group(group)) legs = r.children(group);
    sort_by(legs, kLegOrder);
    return legs;
  };
  // Footfall (1 = swing) and, for Cruse-model files, protraction (1 = protraction).
  for (const char* kind : {"footfall", "protraction"}) {
    std::string g = std::string("/trajectory/") + kind;
    json arr = json::array();
    for (const auto& leg : legs_in(g)) {
      std::string p = g + "/" + leg;
      if (!series_ok(p) || count(r.dims(p)) != n) {
        note_ignored(out, p);
        continue;
      }
      arr.push_back({{"leg", leg}, {"intervals", intervals_json(t, read(p))}});
    }
    tr[kind] = arr;
  }
  // Cruse-model leg positions: 1-D per leg, or n x k (components).
  tr["position"] = json::array();
  for (const auto& leg : legs_in("/trajectory/position")) {
    std::string p = "/trajectory/position/" + leg;
    if (!series_ok(p)) {
      note_ignored(out, p);
      continue;
    }
    auto d = r.dims(p);
    auto v = read(p);
    std::size_t k = d.size() >= 2 ? count(d) / n : 1;
    static const char* comp_names[] = {"x", "y", "z"};
    for (std::size_t c = 0; c < k && c < 3; ++c) {
      std::vector<double> y(m);
      for (std::size_t i = 0; i < m; ++i) y[i] = v[i * k + c];
      json s = series(t, y, max_points);
      s["leg"] = leg;
      s["component"] = k == 1 ? "" : comp_names[c];
      s["units"] = units_of(r, p);
      tr["position"].push_back(s);
    }
  }
  for (const auto& c : r.children("/trajectory")) {
    static const std::set<std::string> known = {"time",     "angles",      "angular_velocity", "states",
                                                "footfall", "protraction", "position"};
    if (!known.count(c)) note_ignored(out, "/trajectory/" + c);
  }
  out["trajectory"] = tr;
}

// ---------------------------------------------------------------- parameters, features
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
    if (is_numeric_dataset(r, p) && count(r.dims(p)) == 1) {
      rows.push_back({{"name", name}, {"value", num(io::read_scalar(r, p))}, {"units", units_of(r, p)}});
    } else if (is_numeric_dataset(r, p) && count(r.dims(p)) <= 64) {  // e.g. phases of six legs
      rows.push_back({{"name", name}, {"value", nums(r.read_doubles(p))}, {"units", units_of(r, p)}});
    } else if (is_dataset(r, p) && is_string_dataset(r, p)) {
      rows.push_back({{"name", name}, {"value", r.read_strings(p)}, {"units", ""}});
    } else {
      note_ignored(out, p);
    }
  }
  out["features"] = rows;
}

// Named per-parameter vectors below `group` (sensitivity/features, sweep/features, ...).
json named_vectors(const H5Reader& r, json& out, const std::string& group, std::size_t expected) {
  json arr = json::array();
  if (!r.is_group(group)) return arr;
  std::vector<std::string> names;
  walk(r, group, "", names);
  for (const auto& name : names) {
    std::string p = group + "/" + name;
    if (!is_numeric_dataset(r, p) || count(r.dims(p)) != expected) {
      note_ignored(out, p);
      continue;
    }
    arr.push_back({{"name", name}, {"units", units_of(r, p)}, {"values", nums(r.read_doubles(p))}});
  }
  return arr;
}

// ---------------------------------------------------------------- sensitivity
void extract_sensitivity(const H5Reader& r, json& out) {
  json s = json::object();
  auto params = strings_or_empty(r, "/sensitivity/parameters");
  s["parameters"] = params;
  s["parameter_units"] = strings_or_empty(r, "/sensitivity/parameter_units");
  s["features"] = named_vectors(r, out, "/sensitivity/features", params.size());
  s["relative"] = named_vectors(r, out, "/sensitivity/relative", params.size());
  const std::string re = "/sensitivity/floquet/multipliers_real", im = "/sensitivity/floquet/multipliers_imag";
  if (is_numeric_dataset(r, re) && is_numeric_dataset(r, im)) {
    auto a = r.read_doubles(re), b = r.read_doubles(im);
    if (a.size() == b.size()) s["floquet"] = {{"real", nums(a)}, {"imag", nums(b)}};
  }
  // Phase response curve: /sensitivity/prc/{phase, shift}, attribute `state` = the kicked state.
  const std::string ph = "/sensitivity/prc/phase", sh = "/sensitivity/prc/shift";
  if (is_numeric_dataset(r, ph) && is_numeric_dataset(r, sh)) {
    auto a = r.read_doubles(ph), b = r.read_doubles(sh);
    std::string state;
    try {
      state = r.read_string_attribute("/sensitivity/prc", "state");
    } catch (const Error&) {
    }
    if (a.size() == b.size())
      s["prc"] = {{"phase", nums(a)}, {"shift", nums(b)}, {"phase_units", units_of(r, ph)},
                  {"shift_units", units_of(r, sh)}, {"state", state}};
  }
  for (const auto& c : r.children("/sensitivity")) {
    // Bookkeeping that the figures already cover (names, units, values, our own ranking).
    static const std::set<std::string> known = {"parameters",     "parameter_units", "parameter_method",
                                                "parameter_values", "feature_names",  "feature_units",
                                                "feature_values", "units",           "ranking",
                                                "features",       "relative",        "floquet",
                                                "prc"};
    if (!known.count(c)) note_ignored(out, "/sensitivity/" + c);
  }
  out["sensitivity"] = s;
}

// ---------------------------------------------------------------- fit
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
    if (count(r.dims("/fit/correlation")) == names.size() * names.size())
      f["correlation"] = vec("/fit/correlation");
    else
      note_ignored(out, "/fit/correlation (not n x n for the n parameter_names)");
  }
  f["final_cost"] = vec("/fit/multistart/final_cost");
  f["kinematics"] = json::array();
  if (is_numeric_dataset(r, "/fit/data/time")) {
    auto t = r.read_doubles("/fit/data/time");
    f["time_units"] = units_of(r, "/fit/data/time");
    auto cols = r.children("/fit/data");
    for (const auto& c : cols) {
      if (c == "time") continue;
      std::string dp = "/fit/data/" + c, mp = "/fit/model/" + c;
      if (!is_numeric_dataset(r, dp) || count(r.dims(dp)) != t.size()) {
        note_ignored(out, dp);
        continue;
      }
      json k;
      k["name"] = c;
      k["units"] = units_of(r, dp);
      json d = series(t, r.read_doubles(dp), max_points);
      if (!d.contains("t")) d["t"] = nums(t);
      k["data"] = d;
      if (is_numeric_dataset(r, mp) && count(r.dims(mp)) == t.size()) {
        json m = series(t, r.read_doubles(mp), max_points);
        if (!m.contains("t")) m["t"] = nums(t);
        k["model"] = m;
      }
      f["kinematics"].push_back(k);
    }
  }
  out["fit"] = f;
}

// ---------------------------------------------------------------- sweep
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

void extract_sweep(const H5Reader& r, json& out) {
  json s = json::object();
  auto names = strings_or_empty(r, "/sweep/parameter_names");
  s["parameter_names"] = names;
  s["parameter_units"] = strings_or_empty(r, "/sweep/parameter_units");
  std::size_t n_points = 0;
  json points = json::array();
  if (is_numeric_dataset(r, "/sweep/points") && !names.empty()) {
    auto d = r.dims("/sweep/points");
    auto v = r.read_doubles("/sweep/points");
    std::size_t p = names.size();
    if (count(d) % p == 0) {
      n_points = count(d) / p;
      for (std::size_t i = 0; i < n_points; ++i) {
        json row = json::array();
        for (std::size_t j = 0; j < p; ++j) row.push_back(num(v[i * p + j]));
        points.push_back(row);
      }
    } else {
      note_ignored(out, "/sweep/points (shape does not match parameter_names)");
    }
  }
  s["points"] = points;
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

std::string read_embedded(const std::string& key) {
  const auto& files = embedded::files();
  auto it = files.find(key);
  if (it == files.end()) throw Error("report asset " + key + " is not embedded in this build");
  return it->second;
}

}  // namespace

std::vector<std::size_t> decimate_indices(const std::vector<double>& y, std::size_t max_points) {
  const std::size_t n = y.size();
  std::vector<std::size_t> idx;
  if (n <= max_points || max_points < 4) {
    for (std::size_t i = 0; i < n && (n <= max_points || i < max_points); ++i) idx.push_back(i);
    return idx;
  }
  const std::size_t buckets = (max_points - 2) / 2;
  idx.push_back(0);
  for (std::size_t b = 0; b < buckets; ++b) {
    std::size_t lo = 1 + b * (n - 2) / buckets, hi = 1 + (b + 1) * (n - 2) / buckets;
    if (lo >= hi) continue;
    std::size_t imin = lo, imax = lo;
    bool any = false;
    for (std::size_t i = lo; i < hi; ++i) {
      if (!std::isfinite(y[i])) continue;
      if (!any || y[i] < y[imin]) imin = i;
      if (!any || y[i] > y[imax]) imax = i;
      any = true;
    }
    if (!any) {
      idx.push_back(lo);  // a gap stays a gap
      continue;
    }
    idx.push_back(std::min(imin, imax));
    if (imin != imax) idx.push_back(std::max(imin, imax));
  }
  idx.push_back(n - 1);
  return idx;
}

std::vector<std::pair<double, double>> intervals_where(const std::vector<double>& t, const std::vector<double>& flag) {
  std::vector<std::pair<double, double>> out;
  const std::size_t n = std::min(t.size(), flag.size());
  std::size_t i = 0;
  while (i < n) {
    if (flag[i] >= 0.5) {
      std::size_t j = i;
      while (j + 1 < n && flag[j + 1] >= 0.5) ++j;
      // The phase lasts until the next sample where it is over (or the end of the run).
      out.emplace_back(t[i], j + 1 < n ? t[j + 1] : t[j]);
      i = j + 1;
    } else {
      ++i;
    }
  }
  return out;
}

std::string json_for_script(const nlohmann::json& j) {
  std::string s = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string out;
  out.reserve(s.size() + s.size() / 50);
  for (char c : s) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

namespace {
// A file of a verb whose result group is missing did not finish (e.g. a gsa file of an older
// phasmid killed during its analysis, which left /sweep alone): refused, not drawn as if whole.
void refuse_unfinished(const H5Reader& r, const std::string& h5_path) {
  static const std::map<std::string, std::string> result_of = {{"gsa", "/gsa"}, {"continue", "/continuation"}, {"fit", "/fit"}};
  std::istringstream words(root_attr(r, "command"));
  std::string program, verb;
  words >> program >> verb;
  const auto it = result_of.find(verb);
  if (it == result_of.end() || r.exists(it->second)) return;
  throw Error(h5_path + ": a `phasmid " + verb + "` file without " + it->second + ": the run ended before its result was " +
              "written" + (verb == "gsa" ? "; `phasmid gsa CONFIG -o " + h5_path + " --resume` analyses it" : ""));
}
}  // namespace

nlohmann::json extract(const std::string& h5_path, std::size_t max_points) {
  H5Reader r(h5_path);  // throws phasmid::Error: no such file / not an HDF5 file
  refuse_unfinished(r, h5_path);
  json out = json::object();
  out["source"] = std::filesystem::path(h5_path).filename().string();
  out["attrs"] = {{"phasmid_version", root_attr(r, "phasmid_version")},
                  {"command", root_attr(r, "command")},
                  {"created", root_attr(r, "created")},
                  {"config", root_attr(r, "config")}};
  out["ignored"] = json::array();
  out["max_points"] = max_points;
  for (const auto& top : r.children("/")) {
    const std::string p = "/" + top;
    if (!r.is_group(p)) {
      note_ignored(out, p);
      continue;
    }
    // A group this report cannot read (unexpected types or shapes) is listed, not fatal.
    try {
      if (top == "trajectory")
        extract_trajectory(r, out, max_points);
      else if (top == "parameters")
        extract_parameters(r, out);
      else if (top == "features")
        extract_features(r, out);
      else if (top == "sensitivity")
        extract_sensitivity(r, out);
      else if (top == "fit")
        extract_fit(r, out, max_points);
      else if (top == "sweep")
        extract_sweep(r, out);
      else if (top == "gsa")
        out["gsa"] = extract_gsa(r);
      else if (top == "continuation")
        extract_continuation(r, out);
      else
        note_ignored(out, p);
    } catch (const Error& e) {
      out.erase(top);
      note_ignored(out, p + " (unreadable: " + e.what() + ")");
    }
  }
  return out;
}

std::string render_html(const nlohmann::json& data) {
  std::string tpl = read_embedded("reports/report.html");
  const std::vector<std::pair<std::string, std::string>> parts = {
      {"/*PHASMID_CSS*/", read_embedded("reports/report.css")},
      {"/*PHASMID_VENDOR_JS*/",
       read_embedded("reports/vendor/chart.umd.min.js") + "\n" +
           read_embedded("reports/vendor/chartjs-chart-matrix.min.js")},
      {"/*PHASMID_REPORT_JS*/", read_embedded("reports/report.js")},
      {"/*PHASMID_DATA*/", json_for_script(data)},
      {"PHASMID_TITLE", [&] {
         std::string s = "phasmid report: " + data.value("source", std::string());
         std::string e;
         for (char c : s) {
           if (c == '<') e += "&lt;";
           else if (c == '>') e += "&gt;";
           else if (c == '&') e += "&amp;";
           else e += c;
         }
         return e;
       }()}};
  // One pass over the template: inserted text is never scanned for markers again.
  std::string out;
  std::size_t pos = 0;
  while (true) {
    std::size_t best = std::string::npos;
    const std::pair<std::string, std::string>* which = nullptr;
    for (const auto& p : parts) {
      auto f = tpl.find(p.first, pos);
      if (f < best) best = f, which = &p;
    }
    if (!which) break;
    out.append(tpl, pos, best - pos);
    out += which->second;
    pos = best + which->first.size();
  }
  out.append(tpl, pos, std::string::npos);
  return out;
}

std::string default_output_path(const std::string& h5_path) {
  std::filesystem::path p(h5_path);
  p.replace_extension(".html");
  return p.string();
}

void write_report(const std::string& h5_path, const std::string& html_path) {
  io::check_output_path(html_path, {h5_path});
  const std::string html = render_html(extract(h5_path));  // reads only the input: its errors first
  io::HeldOutputLock lock(html_path);  // before "<html>.tmp" (the locked file) is written; makes the directory
  const std::string tmp = lock.get().tmp_path();
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw Error("cannot write " + tmp);
    f.write(html.data(), static_cast<std::streamsize>(html.size()));
    f.close();
    if (!f) {
      std::remove(tmp.c_str());
      throw Error("cannot write " + tmp);
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, html_path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw Error("cannot rename " + tmp + " to " + html_path + ": " + ec.message());
  }
}

}  // namespace phasmid::report
