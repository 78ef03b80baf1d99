#include "report/panels.hpp"

#include <algorithm>
#include <cctype>
#include <set>

#include "io/h5_file.hpp"
#include "io/h5_stream.hpp"
#include "report/panel_common.hpp"
#include "report/report.hpp"

namespace phasmid::report {
namespace {

using nlohmann::json;
using io::H5Reader;

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

json intervals_json(const std::vector<double>& t, const std::vector<double>& flag) {
  json a = json::array();
  for (auto& [a0, a1] : intervals_where(t, flag)) a.push_back({num(a0), num(a1)});
  return a;
}

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

// The trajectory's time as read, and how every series of it is read alike: a trajectory longer
// than kMaxReadSamples is read every stride-th sample (by hyperslab), so that what the report
// allocates per series is bounded whatever the file declares.
struct Trajectory {
  const H5Reader& r;
  json& out;
  std::size_t max_points;
  std::size_t n = 0;  // samples in the file
  hsize_t stride = 1;
  std::vector<double> t;  // samples read

  Trajectory(const H5Reader& reader, json& o, std::size_t max) : r(reader), out(o), max_points(max) {
    const std::vector<hsize_t> time_dims = r.dims("/trajectory/time");
    n = n_elements(time_dims);
    stride = time_dims.size() == 1 && n > kMaxReadSamples ? (n + kMaxReadSamples - 1) / kMaxReadSamples : 1;
    t = read("/trajectory/time");
  }
  std::vector<double> read(const std::string& path) const {
    return stride == 1 ? r.read_doubles(path) : io::read_strided(r, path, stride);
  }
  // A numeric dataset with one row per time sample.
  bool series_ok(const std::string& path) const {
    return is_numeric_dataset(r, path) && !r.dims(path).empty() && r.dims(path)[0] == n;
  }
  // series_ok and one value per sample; else `path` is listed as ignored.
  bool one_per_sample(const std::string& path) const {
    if (series_ok(path) && n_elements(r.dims(path)) == n) return true;
    note_ignored(out, path);
    return false;
  }
  std::vector<std::string> legs_in(const std::string& group) const {
    std::vector<std::string> legs;
    if (r.is_group(group)) legs = r.children(group);
    sort_by(legs, kLegOrder);
    return legs;
  }
};

// /trajectory/<kind>/<leg>/<joint> (angles, angular_velocity), legs and joints in body order.
json joint_series(const Trajectory& tj, const char* kind) {
  const std::string group = std::string("/trajectory/") + kind;
  json arr = json::array();
  for (const auto& leg : tj.legs_in(group)) {
    std::string lp = group + "/" + leg;
    if (!tj.r.is_group(lp)) {
      note_ignored(tj.out, lp);
      continue;
    }
    auto joints = tj.r.children(lp);
    sort_by(joints, kJointOrder);
    for (const auto& joint : joints) {
      std::string p = lp + "/" + joint;
      if (!tj.one_per_sample(p)) continue;
      json s = series(tj.t, tj.read(p), tj.max_points);
      s["leg"] = leg;
      s["joint"] = joint;
      s["units"] = units_of(tj.r, p);
      arr.push_back(s);
    }
  }
  return arr;
}

// States: membrane potentials (<...>.<unit>.V) are drawn, CPG and motor-neuron units (C1, cpg_ext,
// MN2, mn_flx, ...) apart from the other neurons (interneurons, sensory units); the rest is listed.
void state_series(const Trajectory& tj, json& tr) {
  tr["voltages"] = json::array();
  tr["other_states"] = json::array();
  if (!tj.r.is_group("/trajectory/states")) return;
  std::vector<std::string> names;
  walk(tj.r, "/trajectory/states", "", names);
  for (const auto& name : names) {
    std::string p = "/trajectory/states/" + name;
    const bool is_voltage = name.size() > 2 && name.compare(name.size() - 2, 2, ".V") == 0;
    if (is_voltage && tj.series_ok(p) && n_elements(tj.r.dims(p)) == tj.n) {
      json s = series(tj.t, tj.read(p), tj.max_points);
      s["name"] = name;
      s["kind"] = is_cpg_or_mn(name) ? "cpg_mn" : "other";
      s["units"] = units_of(tj.r, p);
      tr["voltages"].push_back(s);
    } else {
      tr["other_states"].push_back({{"name", name}, {"units", units_of(tj.r, p)}});
    }
  }
}

// Footfall (1 = swing) and, for Cruse-model files, protraction (1 = protraction) as intervals per leg.
json phase_intervals(const Trajectory& tj, const char* kind) {
  const std::string g = std::string("/trajectory/") + kind;
  json arr = json::array();
  for (const auto& leg : tj.legs_in(g)) {
    std::string p = g + "/" + leg;
    if (!tj.one_per_sample(p)) continue;
    arr.push_back({{"leg", leg}, {"intervals", intervals_json(tj.t, tj.read(p))}});
  }
  return arr;
}

// Cruse-model leg positions: 1-D per leg, or n x k (components).
json positions(const Trajectory& tj) {
  json arr = json::array();
  for (const auto& leg : tj.legs_in("/trajectory/position")) {
    std::string p = "/trajectory/position/" + leg;
    if (!tj.series_ok(p)) {
      note_ignored(tj.out, p);
      continue;
    }
    auto d = tj.r.dims(p);
    auto v = tj.read(p);
    const std::size_t m = tj.t.size();
    std::size_t k = d.size() >= 2 ? n_elements(d) / tj.n : 1;
    static const char* comp_names[] = {"x", "y", "z"};
    for (std::size_t c = 0; c < k && c < 3; ++c) {
      std::vector<double> y(m);
      for (std::size_t i = 0; i < m; ++i) y[i] = v[i * k + c];
      json s = series(tj.t, y, tj.max_points);
      s["leg"] = leg;
      s["component"] = k == 1 ? "" : comp_names[c];
      s["units"] = units_of(tj.r, p);
      arr.push_back(s);
    }
  }
  return arr;
}

}  // namespace

void extract_trajectory(const H5Reader& r, json& out, std::size_t max_points) {
  json tr = json::object();
  if (!is_numeric_dataset(r, "/trajectory/time")) {
    note_ignored(out, "/trajectory (no /trajectory/time)");
    return;
  }
  const Trajectory tj(r, out, max_points);
  const std::vector<double>& t = tj.t;
  const std::size_t m = t.size();  // samples read
  tr["time_units"] = units_of(r, "/trajectory/time");
  tr["t_range"] = {num(t.empty() ? 0 : t.front()), num(t.empty() ? 0 : t.back())};
  tr["decimated"] = m > max_points || tj.stride > 1;
  if (m <= max_points && tj.stride == 1) tr["time"] = nums(t);
  for (const char* kind : {"angles", "angular_velocity"}) tr[kind] = joint_series(tj, kind);
  state_series(tj, tr);
  for (const char* kind : {"footfall", "protraction"}) tr[kind] = phase_intervals(tj, kind);
  tr["position"] = positions(tj);
  for (const auto& c : r.children("/trajectory")) {
    static const std::set<std::string> known = {"time",     "angles",      "angular_velocity", "states",
                                                "footfall", "protraction", "position"};
    if (!known.count(c)) note_ignored(out, "/trajectory/" + c);
  }
  out["trajectory"] = tr;
}

}  // namespace phasmid::report
