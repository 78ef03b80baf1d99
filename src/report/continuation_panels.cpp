#include "report/panels.hpp"

#include <cmath>

#include "common/error.hpp"
#include "io/h5_file.hpp"
#include "report/panel_common.hpp"

namespace phasmid::report {
namespace {
using json = nlohmann::json;

json numbers(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) a.push_back(std::isfinite(x) ? json(x) : json());
  return a;
}

// Rows of an N x M dataset as N arrays.
json rows(const io::H5Reader& r, const std::string& path, size_t n) {
  const std::vector<double> v = r.read_doubles(path);
  if (n == 0 || v.size() % n) throw Error(path + ": not " + std::to_string(n) + " rows");
  const size_t m = v.size() / n;
  json out = json::array();
  for (size_t i = 0; i < n; ++i) out.push_back(numbers(std::vector<double>(v.begin() + i * m, v.begin() + (i + 1) * m)));
  return out;
}

json special_points(const io::H5Reader& r, const std::string& g) {
  json sp = json::array();
  if (!r.exists(g + "/kind")) return sp;
  const auto kind = r.read_strings(g + "/kind");
  const auto note = r.read_strings(g + "/note");
  const auto index = r.read_doubles(g + "/index");
  const auto par = r.read_doubles(g + "/parameter");
  const auto period = r.read_doubles(g + "/period_ms");
  // A damaged or edited file may give the columns different lengths: then no row is trusted.
  if (index.size() != kind.size() || par.size() != kind.size() || period.size() != kind.size())
    throw Error(g + ": kind, index, parameter and period_ms have " + std::to_string(kind.size()) + ", " +
                std::to_string(index.size()) + ", " + std::to_string(par.size()) + " and " +
                std::to_string(period.size()) + " rows");
  for (size_t i = 0; i < kind.size(); ++i)
    sp.push_back({{"kind", kind[i]}, {"note", i < note.size() ? note[i] : ""},
                  {"index", index[i] >= 0 && index[i] < 1e15 ? json(std::floor(index[i])) : json()},
                  {"parameter", std::isfinite(par[i]) ? json(par[i]) : json()},
                  {"period_ms", std::isfinite(period[i]) ? json(period[i]) : json()}});
  return sp;
}

}  // namespace

void extract_continuation(const io::H5Reader& r, json& out) {
  const std::string g = "/continuation";
  const std::vector<double> par = r.read_doubles(g + "/parameter");
  const size_t n = par.size();
  json c;
  c["parameter"] = r.read_string_attribute(g, "parameter");
  c["parameter_units"] = units_of(r, g + "/parameter");
  c["end"] = r.read_string_attribute(g, "end");
  try {  // only in the OUT.partial file of a run still going (docs/continuation.md)
    c["partial"] = r.read_string_attribute(g, "partial");
  } catch (const Error&) {
  }
  c["values"] = numbers(par);
  c["period_ms"] = numbers(r.read_doubles(g + "/period_ms"));
  json stable = json::array();
  for (double s : r.read_doubles(g + "/stable")) stable.push_back(s > 0.5);
  c["stable"] = stable;
  c["features"] = json::array();
  if (r.exists(g + "/features"))
    for (const auto& f : r.children(g + "/features")) {
      const std::string p = g + "/features/" + f;
      c["features"].push_back({{"name", f}, {"units", units_of(r, p)}, {"values", numbers(r.read_doubles(p))}});
    }
  c["multipliers_abs"] = rows(r, g + "/multipliers_abs", n);
  c["multipliers_real"] = rows(r, g + "/multipliers_real", n);
  c["multipliers_imag"] = rows(r, g + "/multipliers_imag", n);
  c["trivial"] = numbers(r.read_doubles(g + "/trivial_multiplier"));
  if (r.exists(g + "/neutral_multipliers")) c["neutral"] = numbers(r.read_doubles(g + "/neutral_multipliers"));
  if (r.exists(g + "/held_phase_fractions")) {
    c["held_fractions"] = numbers(r.read_doubles(g + "/held_phase_fractions"));
    c["held_names"] = r.read_string_attribute(g + "/held_phase_fractions", "names");
  }
  try {  // the branch is worth showing without them
    c["special"] = special_points(r, g + "/special_points");
  } catch (const Error& e) {
    c["special"] = json::array();
    out["ignored"].push_back(g + "/special_points (unreadable: " + e.what() + ")");
  }
  out["continuation"] = c;
}

}  // namespace phasmid::report
