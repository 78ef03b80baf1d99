// [[fit.recording]]: recordings of walking animals as fit targets, compared step cycle by step
// cycle through observables (docs/recordings.md "Fitting the model to a recording").
#include <set>

#include "common/error.hpp"
#include "config/fit_section.hpp"
#include "config/toml_util.hpp"
#include "fit/kinematic_data.hpp"
#include "fit/petab_tables.hpp"
#include "io/text_file.hpp"

namespace phasmid::fit {
namespace {
using config::check_keys;
using config::number;
using config::text;
using config::where;

// The model's leg of a recorded leg: L1/R1 front, L2/R2 middle, L3/R3 hind.
std::string default_model_leg(const std::string& leg) {
  if (leg.size() == 2 && (leg[0] == 'L' || leg[0] == 'R')) {
    if (leg[1] == '1') return "front";
    if (leg[1] == '2') return "middle";
    if (leg[1] == '3') return "hind";
  }
  return leg;
}

Observable observable(const config::Config& cfg, const toml::table& t) {
  check_keys(cfg, t, "fit.recording.observable", {"data", "model", "sign", "offset", "scale", "sigma_deg"});
  Observable o;
  o.origin = where(cfg, t);
  for (const char* req : {"data", "model"})
    if (!t.get(req)) throw Error(o.origin + ": [[fit.recording.observable]] needs '" + req + "'");
  o.data_channel = text(cfg, *t.get("data"), "data");
  o.model_channel = text(cfg, *t.get("model"), "model");
  o.origin = where(cfg, *t.get("data"));
  if (auto n = t.get("sign")) o.sign = number(cfg, *n, "sign");
  if (auto n = t.get("offset")) {
    if (n->is_string()) o.offset_parameter = text(cfg, *n, "offset");
    else o.offset_deg = number(cfg, *n, "offset");
  }
  if (auto n = t.get("scale")) {
    if (n->is_string()) o.scale_parameter = text(cfg, *n, "scale");
    else o.scale = number(cfg, *n, "scale");
  }
  if (auto n = t.get("sigma_deg"); n && n->is_string()) {
    o.sigma_parameter = text(cfg, *n, "sigma_deg");
  } else if (n) {
    o.sigma_deg = number(cfg, *n, "sigma_deg");
    if (o.sigma_deg < 0) throw Error(where(cfg, *n) + ": sigma_deg must be >= 0 (0: the recording's step-to-step SD)");
  }
  return o;
}

// The step-cycle summary of the recording's leg (docs/recordings.md).
features::StepCycles summarise(const KinematicData& d, const std::string& leg, const features::StepCycleOptions& o,
                               const std::string& origin) {
  auto it = d.stances.find(leg);
  if (it == d.stances.end()) throw Error(origin + ": " + d.source + " has no contact data for leg '" + leg + "'");
  std::vector<std::string> channels;
  std::vector<std::vector<double>> samples;
  for (size_t c = 0; c < d.channels.size(); ++c)
    if (d.channels[c].compare(0, leg.size() + 1, leg + ".") == 0)
      channels.push_back(d.channels[c]), samples.push_back(d.angles_deg[c]);
  return features::step_cycles(d.time_ms, channels, samples, it->second, o, d.source + ": " + leg);
}

StepCycleTarget recording_target(const config::Config& cfg, const toml::table& t, const std::string& file_override,
                                 double frame_rate_hz) {
  check_keys(cfg, t, "fit.recording",
             {"file", "leg", "model_leg", "bins", "discard_steps", "max_period_deviation", "period_sigma_ms",
              "duty_factor_sigma", "sigma_floor_deg", "sample_ms", "frame_rate_hz", "observable", "set", "condition"});
  StepCycleTarget s;
  s.origin = where(cfg, t);
  if (auto n = t.get("file")) s.file = resolve_path(cfg, text(cfg, *n, "file"));
  if (!file_override.empty()) s.file = file_override;
  if (s.file.empty()) throw Error(s.origin + ": [[fit.recording]] needs file (or give --data)");
  if (!t.get("leg")) throw Error(s.origin + ": [[fit.recording]] needs leg (the recording's leg, e.g. \"L2\")");
  s.leg = text(cfg, *t.get("leg"), "leg");
  s.model_leg = t.get("model_leg") ? text(cfg, *t.get("model_leg"), "model_leg") : default_model_leg(s.leg);
  features::StepCycleOptions o;
  if (auto n = t.get("bins")) o.bins = static_cast<int>(config::number_in(cfg, *n, "bins", 2, 1000));
  if (auto n = t.get("discard_steps")) o.discard_steps = static_cast<int>(config::number_in(cfg, *n, "discard_steps", 0, 1e6));
  if (auto n = t.get("max_period_deviation")) o.max_period_deviation = number(cfg, *n, "max_period_deviation");
  if (const std::string why = o.invalid_reason(); !why.empty()) throw Error(s.origin + ": " + why);
  if (auto n = t.get("period_sigma_ms")) s.period_sigma_ms = config::number_in(cfg, *n, "period_sigma_ms", 0, 1e9);
  if (auto n = t.get("duty_factor_sigma")) s.duty_factor_sigma = config::number_in(cfg, *n, "duty_factor_sigma", 0, 1);
  if (auto n = t.get("sigma_floor_deg")) s.sigma_floor_deg = config::number_in(cfg, *n, "sigma_floor_deg", 0, 1e3);
  if (auto n = t.get("sample_ms")) s.sample_ms = config::number_in(cfg, *n, "sample_ms", 0.01, 100);
  if (auto n = t.get("frame_rate_hz")) frame_rate_hz = number(cfg, *n, "frame_rate_hz");
  if (auto n = t.get("condition")) s.condition = text(cfg, *n, "condition");
  for (const toml::table* ot : fit_tables(cfg, t, "observable")) s.observables.push_back(observable(cfg, *ot));
  if (s.observables.empty())
    throw Error(s.origin + ": [[fit.recording]] needs at least one [[fit.recording.observable]] (data = \"" + s.leg +
                ".fti\", model = \"" + s.model_leg + ".fti\", sign, offset)");
  const KinematicData d = read_recording(s.file, frame_rate_hz, {s.leg});
  s.data = summarise(d, s.leg, o, s.origin);
  return s;
}

// [fit.conditions.<id>]: PEtab's condition table, one table per condition: model parameter (or
// pattern) = "fit parameter id" (estimated or fixed in [fit.parameters]) or a fixed value.
std::vector<Condition> conditions(const config::Config& cfg, const toml::table& fit) {
  std::vector<Condition> out;
  const toml::node* node = fit.get("conditions");
  if (!node) return out;
  const toml::table* tab = node->as_table();
  if (!tab) throw Error(where(cfg, *node) + ": conditions must be tables [fit.conditions.<id>]");
  for (const auto& [key, value] : *tab) {
    Condition c;
    c.id = std::string(key.str());
    c.origin = where(cfg, value);
    const toml::table* t = value.as_table();
    if (!t) throw Error(c.origin + ": [fit.conditions." + c.id + "] must be a table (model parameter = \"fit parameter\" or value)");
    for (const auto& [name, v] : config::flatten(*t)) {
      if (v->is_string()) c.parameter_ids[name] = text(cfg, *v, name);
      else c.values[name] = number(cfg, *v, name);
    }
    if (c.parameter_ids.empty() && c.values.empty()) throw Error(c.origin + ": condition '" + c.id + "' sets no parameter");
    out.push_back(std::move(c));
  }
  return out;
}

// [fit.petab]: recordings as PEtab observable, measurement and (optional) condition tables
// (fit/petab_tables.hpp), e.g. as `phasmid petab` wrote them.
void load_petab(const config::Config& cfg, const toml::table& fit, FitSpec& spec) {
  const toml::node* node = fit.get("petab");
  if (!node) return;
  const toml::table* t = node->as_table();
  if (!t) throw Error(where(cfg, *node) + ": petab must be a table [fit.petab] (observables, measurements, conditions)");
  check_keys(cfg, *t, "fit.petab", {"observables", "measurements", "conditions", "sample_ms"});
  PetabInput in;
  auto read = [&](const char* key, std::string& text, std::string& origin, bool required) {
    const toml::node* n = t->get(key);
    if (!n) {
      if (required) throw Error(where(cfg, *node) + ": [fit.petab] needs " + key + " (a TSV file)");
      return;
    }
    origin = resolve_path(cfg, config::text(cfg, *n, key));
    text = io::read_text_file(origin, std::string("PEtab ") + key + " table");
    spec.inputs.push_back(origin);
  };
  read("observables", in.observables, in.observables_origin, true);
  read("measurements", in.measurements, in.measurements_origin, true);
  read("conditions", in.conditions, in.conditions_origin, false);
  double sample_ms = StepCycleTarget{}.sample_ms;
  if (auto n = t->get("sample_ms")) sample_ms = config::number_in(cfg, *n, "sample_ms", 0.01, 100);
  parse_petab(in, sample_ms, spec.targets, spec.conditions);
}

}  // namespace

void load_recording_targets(const config::Config& cfg, const toml::table& fit, const FitOverrides& ov, FitSpec& spec) {
  const auto tables = fit_tables(cfg, fit, "recording");
  const bool override_file = !ov.data.empty();
  if (override_file && tables.size() > 1)
    throw Error("--data: the config lists " + std::to_string(tables.size()) + " recordings; edit the config instead");
  for (const toml::table* t : tables) {
    if (!in_target_set(cfg, *t, spec.target_set)) continue;
    spec.targets.step_cycles.push_back(recording_target(cfg, *t, override_file ? ov.data : "", 0));
    spec.inputs.push_back(spec.targets.step_cycles.back().file);
  }
  load_petab(cfg, fit, spec);
  // A condition no recording names is a mistake; one whose recordings are all of another target
  // set is left out.
  std::set<std::string> named, loaded;
  for (const toml::table* t : tables)
    if (auto n = t->get("condition")) named.insert(text(cfg, *n, "condition"));
  for (const auto& t : spec.targets.step_cycles) loaded.insert(t.condition);
  if (!spec.conditions.empty() && fit.get("conditions"))
    throw Error(where(cfg, *fit.get("conditions")) + ": [fit.conditions] and [fit.petab]'s condition table both give conditions; keep one");
  for (const auto& t : spec.targets.step_cycles) named.insert(t.condition);  // [fit.petab]'s
  for (Condition& c : conditions(cfg, fit)) {
    if (!named.count(c.id))
      throw Error(c.origin + ": condition '" + c.id + "' has no targets (give a [[fit.recording]] condition = \"" + c.id + "\")");
    if (loaded.count(c.id)) spec.conditions.push_back(std::move(c));
  }
}

}  // namespace phasmid::fit
