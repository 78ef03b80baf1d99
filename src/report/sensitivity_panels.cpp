#include "report/panels.hpp"

#include <set>

#include "common/error.hpp"
#include "io/h5_file.hpp"
#include "report/panel_common.hpp"

namespace phasmid::report {

using nlohmann::json;
using io::H5Reader;

namespace {

// What was differentiated (attribute mode: steady_cycle or transient; a file without it is
// transient) and, for the steady cycle, its period, Newton residual and section.
void extract_mode(const H5Reader& r, json& s) {
  auto text = [&](const std::string& obj, const std::string& name) {
    return r.has_attribute(obj, name) ? r.read_string_attribute(obj, name) : std::string();
  };
  const std::string mode = text("/sensitivity", "mode");
  s["mode"] = mode.empty() ? "transient" : mode;
  s["mode_note"] = text("/sensitivity", "mode_note");
  const std::string period = "/sensitivity/cycle/period_ms";
  if (mode != "steady_cycle" || !is_numeric_dataset(r, period)) return;
  const auto T = r.read_doubles(period);
  json c = {{"section", text("/sensitivity/cycle", "section")}};
  if (T.size() == 1) c["period_ms"] = nums(T)[0];
  if (r.has_attribute("/sensitivity/cycle", "residual"))
    c["residual"] = nums({r.read_double_attribute("/sensitivity/cycle", "residual")})[0];
  s["cycle"] = c;
}

}  // namespace

void extract_sensitivity(const H5Reader& r, json& out) {
  json s = json::object();
  auto params = strings_or_empty(r, "/sensitivity/parameters");
  s["parameters"] = params;
  s["parameter_units"] = strings_or_empty(r, "/sensitivity/parameter_units");
  s["features"] = named_vectors(r, out, "/sensitivity/features", params.size());
  s["relative"] = named_vectors(r, out, "/sensitivity/relative", params.size());
  extract_mode(r, s);
  // The multipliers of the Floquet analysis, else those of the steady cycle.
  for (const std::string g : {"/sensitivity/floquet", "/sensitivity/cycle"}) {
    const std::string re = g + "/multipliers_real", im = g + "/multipliers_imag";
    if (s.contains("floquet") || !is_numeric_dataset(r, re) || !is_numeric_dataset(r, im)) continue;
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
                                                "prc",            "cycle"};
    if (!known.count(c)) note_ignored(out, "/sensitivity/" + c);
  }
  out["sensitivity"] = s;
}

}  // namespace phasmid::report
