// parse_petab (fit/petab_tables.hpp): PEtab observable, measurement and condition tables back
// into recording targets and conditions.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>

#include "common/error.hpp"
#include "common/format.hpp"
#include "fit/petab_tables.hpp"
#include "fit/text_table.hpp"

namespace phasmid::fit {
namespace {

bool parse_number(const std::string& s, double& v) {
  if (s.empty()) return false;
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(v);
}

bool is_identifier(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  return std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.'; });
}

std::map<std::string, size_t> column_map(const TextTable& t, const std::string& origin, const std::vector<std::string>& required,
                                         const std::string& what) {
  std::map<std::string, size_t> col;
  for (size_t c = 0; c < t.header.size(); ++c) col[t.header[c]] = c;
  for (const auto& r : required)
    if (!col.count(r)) throw Error(origin + ":" + std::to_string(t.header_line) + ": " + what + " table lacks column '" + r + "'");
  return col;
}

std::string cell(const TextRow& row, const std::map<std::string, size_t>& col, const std::string& name) {
  const auto it = col.find(name);
  return it == col.end() ? "" : row.cells[it->second];
}

struct ObservableRow {
  enum Kind { Angle, Period, Duty } kind = Angle;
  std::string id, leg, model_leg, where;
  Observable o;
  bool per_measurement = false;  // noiseParameter1_<id>
  double fixed_noise = 0;        // period / duty factor: a number
};

// "sign * scale * <leg>.<joint> + offset" into o.
void parse_angle_formula(const std::string& f, const std::string& where, ObservableRow& r) {
  std::istringstream is(f);
  std::vector<std::string> tok;
  for (std::string s; is >> s;) tok.push_back(s);
  double v = 0;
  if (tok.size() != 7 || tok[1] != "*" || tok[3] != "*" || tok[5] != "+" || !parse_number(tok[0], v) || (v != 1 && v != -1) ||
      tok[4].find('.') == std::string::npos)
    throw Error(where + ": observableFormula '" + f +
                "' is not 'sign * scale * <leg>.<joint> + offset' (sign 1 or -1), period_ms(<leg>) or duty_factor(<leg>)");
  r.o.sign = v;
  if (parse_number(tok[2], v)) r.o.scale = v;
  else if (is_identifier(tok[2])) r.o.scale_parameter = tok[2];
  else throw Error(where + ": scale '" + tok[2] + "' is neither a number nor a parameter id");
  if (parse_number(tok[6], v)) r.o.offset_deg = v;
  else if (is_identifier(tok[6])) r.o.offset_parameter = tok[6];
  else throw Error(where + ": offset '" + tok[6] + "' is neither a number nor a parameter id");
  r.o.model_channel = tok[4];
  r.model_leg = tok[4].substr(0, tok[4].find('.'));
}

ObservableRow parse_observable(const TextRow& row, const std::map<std::string, size_t>& col, const std::string& origin) {
  ObservableRow r;
  r.where = origin + ":" + std::to_string(row.line);
  r.id = cell(row, col, "observableId");
  const std::string name = cell(row, col, "observableName"), f = cell(row, col, "observableFormula"),
                    noise = cell(row, col, "noiseFormula");
  if (r.id.empty()) throw Error(r.where + ": empty observableId");
  if (name.find('.') == std::string::npos)
    throw Error(r.where + ": observableName '" + name + "' is not the recorded channel (<leg>.<joint>, <leg>.period or <leg>.duty_factor)");
  if (const std::string t = cell(row, col, "observableTransformation"); !t.empty() && t != "lin")
    throw Error(r.where + ": observableTransformation '" + t + "': phasmid's observables are lin");
  if (const std::string d = cell(row, col, "noiseDistribution"); !d.empty() && d != "normal")
    throw Error(r.where + ": noiseDistribution '" + d + "': phasmid's noise is normal");
  r.leg = name.substr(0, name.find('.'));
  const bool period = f.rfind("period_ms(", 0) == 0, duty = f.rfind("duty_factor(", 0) == 0;
  double v = 0;
  r.per_measurement = noise == std::string(kPetabNoisePlaceholder) + r.id;
  if (period || duty) {
    r.kind = period ? ObservableRow::Period : ObservableRow::Duty;
    if (f.back() != ')' || name != r.leg + (period ? ".period" : ".duty_factor"))
      throw Error(r.where + ": observableFormula '" + f + "' and observableName '" + name + "' do not match (" + r.leg +
                  (period ? ".period: period_ms(<model leg>))" : ".duty_factor: duty_factor(<model leg>))"));
    r.model_leg = f.substr(f.find('(') + 1, f.size() - f.find('(') - 2);
    if (!r.per_measurement && !(parse_number(noise, r.fixed_noise) && r.fixed_noise > 0))
      throw Error(r.where + ": noiseFormula '" + noise + "' of a period or duty factor must be a number > 0 or " + std::string(kPetabNoisePlaceholder) + r.id);
    return r;
  }
  parse_angle_formula(f, r.where, r);
  r.o.data_channel = name;
  r.o.origin = r.where;
  if (r.per_measurement) return r;
  if (parse_number(noise, v) && v > 0) r.o.sigma_deg = v;
  else if (is_identifier(noise)) r.o.sigma_parameter = noise;
  else throw Error(r.where + ": noiseFormula '" + noise + "' is neither a number > 0, a parameter id nor " + std::string(kPetabNoisePlaceholder) + r.id);
  return r;
}

std::map<std::string, ObservableRow> parse_observables(const std::string& text, const std::string& origin) {
  const TextTable t = parse_text_table(text, origin, '\t');
  const auto col = column_map(t, origin, {"observableId", "observableName", "observableFormula", "noiseFormula"}, "observable");
  std::map<std::string, ObservableRow> out;
  for (const auto& row : t.rows) {
    ObservableRow r = parse_observable(row, col, origin);
    if (out.count(r.id)) throw Error(r.where + ": observable '" + r.id + "' defined twice (first at " + out.at(r.id).where + ")");
    out.emplace(r.id, std::move(r));
  }
  if (out.empty()) throw Error(origin + ": observable table has no rows");
  return out;
}

// One recording: the measurements of one leg under one condition.
struct Group {
  std::string condition, leg, where;
  std::vector<std::string> observables;  // angle observables, in order of appearance
  std::map<std::string, std::vector<std::array<double, 3>>> bins;  // id -> (time, mean, noise)
  double period = NAN, period_noise = NAN, duty = NAN, duty_noise = NAN;
  const ObservableRow *period_row = nullptr, *duty_row = nullptr;
};

void add_measurement(Group& g, const ObservableRow& ob, const TextRow& row, const std::map<std::string, size_t>& col,
                     const std::string& origin) {
  const std::string where = origin + ":" + std::to_string(row.line), time = cell(row, col, "time");
  const double value = cell_number(row, col.at("measurement"), "measurement", origin);
  double noise = NAN;
  if (ob.per_measurement) {
    noise = col.count("noiseParameters") ? cell_number(row, col.at("noiseParameters"), "noiseParameters", origin) : NAN;
    if (!(noise > 0)) throw Error(where + ": observable '" + ob.id + "' takes its noise from noiseParameters, which must be > 0");
  }
  if (ob.kind != ObservableRow::Angle) {
    if (time != "inf") throw Error(where + ": a period or duty factor is measured on the steady gait: time must be inf");
    double& v = ob.kind == ObservableRow::Period ? g.period : g.duty;
    if (!std::isnan(v)) throw Error(where + ": '" + ob.id + "' measured twice under condition '" + g.condition + "'");
    v = value;
    (ob.kind == ObservableRow::Period ? g.period_noise : g.duty_noise) = ob.per_measurement ? noise : ob.fixed_noise;
    (ob.kind == ObservableRow::Period ? g.period_row : g.duty_row) = &ob;
    return;
  }
  const double t = cell_number(row, col.at("time"), "time", origin);
  if (!g.bins.count(ob.id)) g.observables.push_back(ob.id);
  g.bins[ob.id].push_back({t, value, noise});
}

// The group's step-cycle target: bins at the centres of n equal phase bins of the period.
StepCycleTarget to_target(const Group& g, const std::map<std::string, ObservableRow>& obs, const std::string& origin) {
  const std::string what = g.where + ": leg " + g.leg + " under condition '" + g.condition + "'";
  if (!g.period_row || !g.duty_row) throw Error(what + ": needs a period_ms and a duty_factor measurement (time inf)");
  if (g.observables.empty()) throw Error(what + ": no angle measured");
  StepCycleTarget t;
  t.leg = g.leg;
  t.model_leg = g.period_row->model_leg;
  t.origin = g.where;
  t.file = origin;
  t.condition = g.condition;
  t.sigma_floor_deg = 0;  // the noises are final
  features::StepCycles& d = t.data;
  d.mean_period_ms = d.median_period_ms = g.period;
  d.duty_factor = g.duty;
  d.period_sd_ms = g.period_noise, d.duty_factor_sd = g.duty_noise;
  if (!(g.period > 0)) throw Error(what + ": the period must be > 0");
  const size_t n = g.bins.at(g.observables[0]).size();
  for (size_t k = 0; k < n; ++k) d.phase.push_back((static_cast<double>(k) + 0.5) / static_cast<double>(n));
  for (const auto& id : g.observables) {
    const ObservableRow& ob = obs.at(id);
    if (ob.model_leg != t.model_leg) throw Error(ob.where + ": '" + ob.o.model_channel + "' is not of leg " + t.model_leg + " (the period's)");
    auto bins = g.bins.at(id);
    std::sort(bins.begin(), bins.end());
    if (bins.size() != n) throw Error(what + ": '" + id + "' has " + std::to_string(bins.size()) + " phase bins, '" + g.observables[0] + "' " + std::to_string(n));
    d.channels.push_back(ob.o.data_channel);
    d.mean_deg.emplace_back(), d.sd_deg.emplace_back();
    for (size_t k = 0; k < n; ++k) {
      if (std::abs(bins[k][0] / g.period - d.phase[k]) > 1e-9)
        throw Error(what + ": '" + id + "' at time " + format_g(bins[k][0]) + " ms is not the centre of phase bin " +
                    std::to_string(k + 1) + " of " + std::to_string(n) + " (time = phase x the period measurement)");
      d.mean_deg.back().push_back(bins[k][1]);
      d.sd_deg.back().push_back(bins[k][2]);
    }
    t.observables.push_back(ob.o);
  }
  if (!g.period_row->per_measurement) t.period_sigma_ms = g.period_noise;
  if (!g.duty_row->per_measurement) t.duty_factor_sigma = g.duty_noise;
  return t;
}

std::vector<Condition> parse_conditions(const std::string& text, const std::string& origin) {
  const TextTable t = parse_text_table(text, origin, '\t');
  const auto col = column_map(t, origin, {"conditionId"}, "condition");
  std::vector<Condition> out;
  for (const auto& row : t.rows) {
    Condition c;
    c.origin = origin + ":" + std::to_string(row.line);
    c.id = cell(row, col, "conditionId");
    if (c.id.empty()) throw Error(c.origin + ": empty conditionId");
    for (size_t k = 0; k < t.header.size(); ++k) {
      const std::string& v = row.cells[k];
      double x = 0;
      if (t.header[k] == "conditionId" || t.header[k] == "conditionName" || v.empty()) continue;
      if (parse_number(v, x)) c.values[t.header[k]] = x;
      else if (is_identifier(v)) c.parameter_ids[t.header[k]] = v;
      else throw Error(c.origin + ": '" + v + "' in column '" + t.header[k] + "' is neither a number nor a parameter id");
    }
    if (std::any_of(out.begin(), out.end(), [&](const Condition& o) { return o.id == c.id; }))
      throw Error(c.origin + ": condition '" + c.id + "' listed twice");
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace

void parse_petab(const PetabInput& in, double sample_ms, Targets& targets, std::vector<Condition>& conditions) {
  const auto obs = parse_observables(in.observables, in.observables_origin);
  std::vector<Condition> table = in.conditions.empty() ? std::vector<Condition>{} : parse_conditions(in.conditions, in.conditions_origin);
  const std::string& origin = in.measurements_origin;
  const TextTable t = parse_text_table(in.measurements, origin, '\t');
  const auto col = column_map(t, origin, {"observableId", "simulationConditionId", "measurement", "time"}, "measurement");
  std::vector<Group> groups;
  for (const auto& row : t.rows) {
    const std::string where = origin + ":" + std::to_string(row.line), id = cell(row, col, "observableId"),
                      cond = cell(row, col, "simulationConditionId");
    const auto ob = obs.find(id);
    if (ob == obs.end()) throw Error(where + ": observable '" + id + "' is not in the observable table");
    if (cond.empty()) throw Error(where + ": empty simulationConditionId");
    if (!in.conditions.empty() && std::none_of(table.begin(), table.end(), [&](const Condition& c) { return c.id == cond; }))
      throw Error(where + ": condition '" + cond + "' is not in the condition table");
    auto g = std::find_if(groups.begin(), groups.end(), [&](const Group& x) { return x.condition == cond && x.leg == ob->second.leg; });
    if (g == groups.end()) g = groups.insert(groups.end(), Group{cond, ob->second.leg, where, {}, {}, NAN, NAN, NAN, NAN, nullptr, nullptr});
    add_measurement(*g, ob->second, row, col, origin);
  }
  if (groups.empty()) throw Error(origin + ": measurement table has no rows");
  // A condition of the table that sets nothing is the model as configured. Without a table the
  // conditions keep their ids, for [fit.conditions] to define (or none: the model as configured).
  for (const Group& g : groups) {
    targets.step_cycles.push_back(to_target(g, obs, origin));
    targets.step_cycles.back().sample_ms = sample_ms;
    const auto c = std::find_if(table.begin(), table.end(), [&](const Condition& k) { return k.id == g.condition; });
    if (c != table.end() && c->parameter_ids.empty() && c->values.empty()) targets.step_cycles.back().condition.clear();
  }
  for (auto& c : table)
    if (!c.parameter_ids.empty() || !c.values.empty()) conditions.push_back(std::move(c));
}

}  // namespace phasmid::fit
