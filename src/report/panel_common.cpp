#include "report/panel_common.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "common/error.hpp"
#include "report/report.hpp"

namespace phasmid::report {

using nlohmann::json;
using io::H5Reader;

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

std::size_t n_elements(const std::vector<hsize_t>& d) {
  std::size_t n = 1;
  for (auto x : d) n *= static_cast<std::size_t>(x);
  return n;
}

std::vector<std::string> strings_or_empty(const H5Reader& r, const std::string& path) {
  if (!is_dataset(r, path) || !is_string_dataset(r, path)) return {};
  return r.read_strings(path);
}

// phasmid nests its groups at most four deep; a damaged file can link a group into itself, so
// the walk is bounded in depth and in the number of datasets instead of following the cycle for
// ever.
void walk(const H5Reader& r, const std::string& group, const std::string& prefix, std::vector<std::string>& out,
          int depth) {
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

void note_ignored(json& out, const std::string& path) { out["ignored"].push_back(path); }

json named_vectors(const H5Reader& r, json& out, const std::string& group, std::size_t expected) {
  json arr = json::array();
  if (!r.is_group(group)) return arr;
  std::vector<std::string> names;
  walk(r, group, "", names);
  for (const auto& name : names) {
    std::string p = group + "/" + name;
    if (!is_numeric_dataset(r, p) || n_elements(r.dims(p)) != expected) {
      note_ignored(out, p);
      continue;
    }
    arr.push_back({{"name", name}, {"units", units_of(r, p)}, {"values", nums(r.read_doubles(p))}});
  }
  return arr;
}

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

}  // namespace phasmid::report
