#include "fit/parameter_table.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "common/error.hpp"
#include "io/text_file.hpp"
#include "fit/text_table.hpp"

namespace phasmid::fit {

Scale parse_scale(const std::string& s) {
  if (s == "lin") return Scale::Lin;
  if (s == "log") return Scale::Log;
  if (s == "log10") return Scale::Log10;
  throw Error("parameterScale must be lin, log or log10, got '" + s + "'");
}

const char* scale_name(Scale s) {
  switch (s) {
    case Scale::Lin: return "lin";
    case Scale::Log: return "log";
    case Scale::Log10: return "log10";
  }
  return "?";
}

double to_scaled(Scale s, double theta) {
  switch (s) {
    case Scale::Lin: return theta;
    case Scale::Log: return std::log(theta);
    case Scale::Log10: return std::log10(theta);
  }
  return theta;
}

double from_scaled(Scale s, double x) {
  switch (s) {
    case Scale::Lin: return x;
    case Scale::Log: return std::exp(x);
    case Scale::Log10: return std::pow(10.0, x);
  }
  return x;
}

double dtheta_dx(Scale s, double x) {
  switch (s) {
    case Scale::Lin: return 1.0;
    case Scale::Log: return std::exp(x);
    case Scale::Log10: return std::pow(10.0, x) * std::log(10.0);
  }
  return 1.0;
}

namespace {
// Iterative, with backtracking to the last '*' only: a '*' that matched too little is
// extended by one character, and earlier stars never need revisiting (any later match they
// allow, the last star allows too). Time O(|pat| |s|); the recursive form was exponential in
// the number of stars ("a*a*a*...b" against "aaaa..."), an id a user or a file can supply.
bool glob_match(const char* pat, const char* s) {
  const char* star = nullptr;  // position after the last '*' seen
  const char* resume = nullptr;  // where in s that star's match would end next
  while (*s) {
    if (*pat == '*') {
      star = ++pat;
      resume = s;
    } else if (*pat != '\0' && (*pat == '?' || *pat == *s)) {
      ++pat;
      ++s;
    } else if (star) {
      pat = star;
      s = ++resume;
    } else {
      return false;
    }
  }
  while (*pat == '*') ++pat;
  return *pat == '\0';
}
}  // namespace

bool is_parameter_pattern(const std::string& id) { return id.find_first_of("*?") != std::string::npos; }

bool parameter_id_matches(const std::string& id, const std::string& name) {
  return is_parameter_pattern(id) ? glob_match(id.c_str(), name.c_str()) : id == name;
}

void validate(const FitParameter& p) {
  const std::string w = p.origin.empty() ? "" : p.origin + ": ";
  auto fail = [&](const std::string& m) { throw Error(w + "parameter '" + p.id + "': " + m); };
  if (std::isnan(p.lower) || std::isnan(p.upper) || std::isnan(p.nominal)) fail("bounds and nominal value must be numbers");
  if (!(p.lower <= p.upper)) fail("lowerBound exceeds upperBound");
  if (p.estimate && (p.nominal < p.lower || p.nominal > p.upper))
    fail("nominalValue " + std::to_string(p.nominal) + " outside [lowerBound, upperBound]");
  if (p.scale != Scale::Lin && p.estimate && !(p.lower > 0))
    fail(std::string("parameterScale ") + scale_name(p.scale) + " needs lowerBound > 0");
  if (p.estimate && (!std::isfinite(to_scaled(p.scale, p.lower)) || !std::isfinite(to_scaled(p.scale, p.upper))))
    fail("estimated parameters need finite bounds");
}

std::vector<FitParameter> parse_parameter_table(const std::string& text, const std::string& origin) {
  TextTable t = parse_text_table(text, origin, '\t');
  const char* required[] = {"parameterId", "parameterScale", "lowerBound", "upperBound", "nominalValue", "estimate"};
  std::map<std::string, size_t> col;
  for (size_t c = 0; c < t.header.size(); ++c) col[t.header[c]] = c;
  for (const char* r : required)
    if (!col.count(r))
      throw Error(origin + ":" + std::to_string(t.header_line) + ": parameter table lacks column '" + r +
                  "' (PEtab: parameterId, parameterScale, lowerBound, upperBound, nominalValue, estimate)");
  std::vector<FitParameter> out;
  std::map<std::string, std::string> seen;
  for (const auto& row : t.rows) {
    const std::string where = origin + ":" + std::to_string(row.line);
    FitParameter p;
    p.origin = where;
    p.id = row.cells[col["parameterId"]];
    if (p.id.empty()) throw Error(where + ": empty parameterId");
    if (seen.count(p.id)) throw Error(where + ": parameter '" + p.id + "' listed twice (first at " + seen[p.id] + ")");
    seen[p.id] = where;
    try {
      p.scale = parse_scale(row.cells[col["parameterScale"]]);
    } catch (const Error& e) {
      throw Error(where + ": " + e.what());
    }
    p.lower = cell_number(row, col["lowerBound"], "lowerBound", origin);
    p.upper = cell_number(row, col["upperBound"], "upperBound", origin);
    p.nominal = cell_number(row, col["nominalValue"], "nominalValue", origin);
    const std::string& est = row.cells[col["estimate"]];
    if (est == "1") p.estimate = true;
    else if (est == "0") p.estimate = false;
    else throw Error(where + ": estimate must be 0 or 1, got '" + est + "'");
    auto optional = [&](const char* c) { return col.count(c) ? row.cells[col[c]] : std::string(); };
    p.prior = parse_prior(optional("objectivePriorType"), optional("objectivePriorParameters"), where);
    validate(p);
    out.push_back(p);
  }
  if (out.empty()) throw Error(origin + ": parameter table has no rows");
  return out;
}

std::vector<FitParameter> read_parameter_table(const std::string& path) {
  return parse_parameter_table(io::read_text_file(path, "parameter table"), path);
}

std::string format_parameter_table(const std::vector<FitParameter>& params) {
  std::ostringstream os;
  os.precision(12);
  bool priors = false;
  for (auto& p : params) priors = priors || p.prior.declared;
  os << "parameterId\tparameterScale\tlowerBound\tupperBound\tnominalValue\testimate"
     << (priors ? "\tobjectivePriorType\tobjectivePriorParameters" : "") << "\n";
  for (auto& p : params) {
    os << p.id << '\t' << scale_name(p.scale) << '\t' << p.lower << '\t' << p.upper << '\t' << p.nominal << '\t'
       << (p.estimate ? 1 : 0);
    if (priors) os << '\t' << (p.prior.declared ? prior_name(p.prior.type) : "") << '\t' << format_prior_parameters(p.prior);
    os << '\n';
  }
  return os.str();
}

}  // namespace phasmid::fit
