#include "config/fit_section.hpp"

#include <algorithm>
#include <filesystem>
#include <limits>
#include <map>
#include <set>

#include "common/error.hpp"
#include "config/cruse_section.hpp"
#include "model/ode_model.hpp"
#include "build_info.hpp"

namespace phasmid::fit {
namespace fs = std::filesystem;
using config::number;
using config::where;
using config::check_keys;
using config::text;

namespace {

using config::boolean;

long integer(const config::Config& cfg, const toml::node& n, const std::string& key, long lo) {
  auto v = n.value<int64_t>();
  if (!v || *v < lo) throw Error(where(cfg, n) + ": '" + key + "' must be an integer >= " + std::to_string(lo));
  return static_cast<long>(*v);
}

}  // namespace

// Tables of [[fit.x]] (array of tables) or [fit.x] (one table).
std::vector<const toml::table*> fit_tables(const config::Config& cfg, const toml::table& fit, const std::string& key) {
  std::vector<const toml::table*> out;
  const toml::node* n = fit.get(key);
  if (!n) return out;
  if (auto t = n->as_table()) {
    out.push_back(t);
  } else if (auto a = n->as_array()) {
    for (auto& e : *a) {
      if (!e.as_table()) throw Error(where(cfg, e) + ": entries of fit." + key + " must be tables");
      out.push_back(e.as_table());
    }
  } else {
    throw Error(where(cfg, *n) + ": fit." + key + " must be a table or an array of tables ([[fit." + key + "]])");
  }
  return out;
}

namespace {

// The target sets a target table belongs to: `set = "NAME"` or `set = ["A", "B"]`; default "default".
std::vector<std::string> target_sets_of(const config::Config& cfg, const toml::table& t) {
  const toml::node* n = t.get("set");
  if (!n) return {"default"};
  std::vector<std::string> out;
  if (auto a = n->as_array()) {
    for (auto& e : *a) out.push_back(text(cfg, e, "set"));
    if (out.empty()) throw Error(where(cfg, *n) + ": 'set' must name at least one target set");
  } else {
    out.push_back(text(cfg, *n, "set"));
  }
  return out;
}

}  // namespace

bool in_target_set(const config::Config& cfg, const toml::table& t, const std::string& set) {
  const auto sets = target_sets_of(cfg, t);
  return std::find(sets.begin(), sets.end(), set) != sets.end();
}

namespace {

std::set<std::string> sets_named(const config::Config& cfg, const toml::table& fit, const std::vector<std::string>& keys) {
  std::set<std::string> s;
  for (const auto& key : keys)
    for (auto* t : fit_tables(cfg, fit, key))
      for (auto& name : target_sets_of(cfg, *t)) s.insert(name);
  return s;
}

bool is_param_spec(const toml::table& t) {
  for (const char* k : {"scale", "lower", "upper", "nominal", "estimate", "prior", "prior_parameters"})
    if (t.contains(k)) return true;
  return false;
}

// prior = "normal", prior_parameters = [mean, sd]: PEtab's objectivePriorType and
// objectivePriorParameters (fit/prior.hpp), checked by the same parser.
Prior inline_prior(const config::Config& cfg, const toml::table& t) {
  const toml::node* type = t.get("prior");
  const toml::node* params = t.get("prior_parameters");
  if (!type && !params) return Prior{};
  if (!type) throw Error(where(cfg, *params) + ": prior_parameters without prior");
  if (!params) throw Error(where(cfg, *type) + ": prior needs prior_parameters = [a, b]");
  const toml::array* a = params->as_array();
  if (!a || a->size() != 2)
    throw Error(where(cfg, *params) + ": prior_parameters must be a list of two numbers [a, b]");
  Prior p;
  p.a = number(cfg, *a->get(0), "prior_parameters");
  p.b = number(cfg, *a->get(1), "prior_parameters");
  return parse_prior(text(cfg, *type, "prior"), format_prior_parameters({true, p.type, p.a, p.b}), where(cfg, *type));
}

void inline_parameters(const config::Config& cfg, const toml::table& t, const std::string& prefix,
                       const ModelValue& model_value, std::vector<std::pair<size_t, FitParameter>>& out) {
  for (auto& [k, v] : t) {
    std::string name = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    const toml::table* sub = v.as_table();
    if (!sub) throw Error(where(cfg, v) + ": [fit.parameters] entry '" + name + "' must be a table {scale, lower, upper, nominal, estimate}");
    if (!is_param_spec(*sub)) {
      inline_parameters(cfg, *sub, name, model_value, out);
      continue;
    }
    check_keys(cfg, *sub, "fit.parameters." + name,
               {"scale", "lower", "upper", "nominal", "estimate", "prior", "prior_parameters"});
    FitParameter p;
    p.id = name;
    p.origin = where(cfg, v);
    if (auto n = sub->get("scale")) {
      try {
        p.scale = parse_scale(text(cfg, *n, "scale"));
      } catch (const Error& e) {
        throw Error(where(cfg, *n) + ": " + e.what());
      }
    }
    if (auto n = sub->get("estimate")) p.estimate = boolean(cfg, *n, "estimate");
    // Default start: the model's value (for a pattern, that of the first match).
    if (auto n = sub->get("nominal")) p.nominal = number(cfg, *n, "nominal");
    else p.nominal = model_value(name);
    if (auto n = sub->get("lower")) p.lower = number(cfg, *n, "lower");
    else if (p.estimate) throw Error(p.origin + ": estimated parameter '" + name + "' needs lower");
    else p.lower = p.nominal;
    if (auto n = sub->get("upper")) p.upper = number(cfg, *n, "upper");
    else if (p.estimate) throw Error(p.origin + ": estimated parameter '" + name + "' needs upper");
    else p.upper = p.nominal;
    p.prior = inline_prior(cfg, *sub);
    validate(p);
    out.emplace_back(v.source().begin.line, p);
  }
}

}  // namespace

std::string resolve_path(const config::Config& cfg, const std::string& path) {
  fs::path p(path);
  if (p.is_absolute()) return path;
  const std::string emb = "embedded:";
  if (cfg.path.rfind(emb, 0) == 0) {
    if (fs::exists(p)) return path;
    fs::path src = fs::path(PHASMID_SOURCE_DIR) / fs::path(cfg.path.substr(emb.size())).parent_path() / p;
    return src.string();
  }
  return (fs::path(cfg.path).parent_path() / p).lexically_normal().string();
}

const toml::table& fit_section(const config::Config& cfg) {
  static const toml::table kEmpty;
  const toml::table* fp = cfg.table["fit"].as_table();
  if (cfg.table.contains("fit") && !fp) throw Error(cfg.path + ": [fit] must be a table");
  return fp ? *fp : kEmpty;
}

void check_overrides(const FitOverrides& ov) {
  auto at_least = [](const char* option, const std::optional<long>& v, long lo) {
    if (v && *v < lo) throw Error(std::string(option) + " " + std::to_string(*v) + ": must be an integer >= " + std::to_string(lo));
  };
  at_least("--multistart", ov.multistart, 1);
  at_least("--max-iterations", ov.max_iterations, 1);
  at_least("--seed", ov.seed, 0);
  if (ov.max_iterations && *ov.max_iterations > std::numeric_limits<int>::max())
    throw Error("--max-iterations " + std::to_string(*ov.max_iterations) + ": must be at most " +
                std::to_string(std::numeric_limits<int>::max()));
  if (ov.threads < 0) throw Error("-j/--threads " + std::to_string(ov.threads) + ": must be >= 0 (0: the default)");
}

void load_fit_common(const config::Config& cfg, const toml::table& fit, const FitOverrides& ov,
                     const std::vector<std::string>& target_keys, const ModelValue& model_value, FitSpec& spec) {
  check_overrides(ov);
  // Optimizer and multistart.
  auto get = [&](const char* k) { return fit.get(k); };
  try {
    if (!ov.optimizer.empty()) parse_optimizer(ov.optimizer, spec.optimizer);
    else if (auto n = get("optimizer")) parse_optimizer(text(cfg, *n, "optimizer"), spec.optimizer);
  } catch (const Error& e) {
    if (!ov.optimizer.empty()) throw Error(std::string("--optimizer: ") + e.what());
    throw Error(where(cfg, *get("optimizer")) + ": " + e.what());
  }
  if (auto n = get("max_iterations")) spec.optimizer.max_iterations = static_cast<int>(integer(cfg, *n, "max_iterations", 1));
  if (ov.max_iterations) spec.optimizer.max_iterations = static_cast<int>(*ov.max_iterations);
  if (auto n = get("max_evaluations")) spec.optimizer.max_evaluations = static_cast<int>(integer(cfg, *n, "max_evaluations", 1));
  if (auto n = get("function_tolerance")) spec.optimizer.function_tolerance = number(cfg, *n, "function_tolerance");
  if (auto n = get("parameter_tolerance")) spec.optimizer.parameter_tolerance = number(cfg, *n, "parameter_tolerance");
  if (auto n = get("gradient_tolerance")) spec.optimizer.gradient_tolerance = number(cfg, *n, "gradient_tolerance");
  if (auto n = get("initial_trust_region_radius")) {
    spec.optimizer.initial_trust_region_radius = number(cfg, *n, "initial_trust_region_radius");
    if (!(spec.optimizer.initial_trust_region_radius > 0)) throw Error(where(cfg, *n) + ": initial_trust_region_radius must be > 0");
  }
  if (auto n = get("loss")) spec.optimizer.loss = text(cfg, *n, "loss");
  if (auto n = get("loss_scale")) spec.optimizer.loss_scale = number(cfg, *n, "loss_scale");
  {
    static const std::set<std::string> losses = {"none", "huber", "cauchy", "soft_l1", "arctan"};
    if (!losses.count(spec.optimizer.loss))
      throw Error(where(cfg, *get("loss")) + ": loss must be none, huber, cauchy, soft_l1 or arctan");
    if (spec.optimizer.loss != "none" && !optimizer_info(spec.optimizer).robust_loss)
      throw Error(where(cfg, *get("loss")) + ": robust losses need one of " +
                  optimizer_list([](const OptimizerInfo& a) { return a.robust_loss; }) + ", not " + spec.optimizer.method);
  }
  if (auto n = get("multistart")) spec.multistart.starts = static_cast<size_t>(integer(cfg, *n, "multistart", 1));
  if (ov.multistart) spec.multistart.starts = static_cast<size_t>(*ov.multistart);
  if (auto n = get("sampling")) {
    try {
      spec.multistart.sampling = parse_sampling(text(cfg, *n, "sampling"));
    } catch (const Error& e) {
      throw Error(where(cfg, *n) + ": " + e.what());
    }
  }
  if (auto n = get("seed")) spec.multistart.seed = static_cast<std::uint64_t>(integer(cfg, *n, "seed", 0));
  if (ov.seed) spec.multistart.seed = static_cast<std::uint64_t>(*ov.seed);
  if (auto n = get("threads")) spec.multistart.threads = static_cast<int>(integer(cfg, *n, "threads", 0));
  if (ov.threads > 0) spec.multistart.threads = ov.threads;
  if (auto n = get("absolute_sigma")) spec.absolute_sigma = boolean(cfg, *n, "absolute_sigma");
  if (auto n = get("profile")) {
    auto a = n->as_array();
    if (!a) throw Error(where(cfg, *n) + ": profile must be an array of parameter names");
    for (auto& e : *a) spec.profile.push_back(text(cfg, e, "profile"));
  }
  if (auto n = get("profile_points")) spec.profile_points = static_cast<size_t>(integer(cfg, *n, "profile_points", 3));
  if (auto n = get("profile_span")) spec.profile_span = number(cfg, *n, "profile_span");
  if (auto n = get("output_dt_ms")) {
    spec.output_dt_ms = number(cfg, *n, "output_dt_ms");
    if (!(spec.output_dt_ms > 0)) throw Error(where(cfg, *n) + ": output_dt_ms must be > 0");
  }
  if (auto n = get("sensitivity_error_control"))
    spec.problem.solver.sensitivity_error_control = boolean(cfg, *n, "sensitivity_error_control");
  if (auto n = get("min_swing_deg")) spec.problem.feature_options.min_swing_deg = number(cfg, *n, "min_swing_deg");
  if (auto n = get("min_swing_fraction")) spec.problem.feature_options.min_swing_fraction = number(cfg, *n, "min_swing_fraction");

  // Target set.
  if (auto n = get("target_set")) spec.target_set = text(cfg, *n, "target_set");
  if (!ov.target_set.empty()) spec.target_set = ov.target_set;
  {
    std::set<std::string> sets = sets_named(cfg, fit, target_keys);
    if (!sets.empty() && !sets.count(spec.target_set)) {
      std::string list;
      for (auto& s : sets) list += (list.empty() ? "" : ", ") + s;
      throw Error(cfg.path + ": no targets in set '" + spec.target_set + "' (sets: " + list + ")");
    }
  }

  // Parameters: --parameters, else the config's table file plus inline entries (inline wins).
  if (!ov.parameters.empty()) {
    spec.parameters = read_parameter_table(ov.parameters);
    spec.inputs.push_back(ov.parameters);
  } else {
    std::vector<FitParameter> table;
    std::vector<std::pair<size_t, FitParameter>> inl;
    if (auto n = get("parameter_table")) {
      std::string path = resolve_path(cfg, text(cfg, *n, "parameter_table"));
      table = read_parameter_table(path);
      spec.inputs.push_back(path);
    }
    if (auto n = get("parameters")) {
      auto t = n->as_table();
      if (!t) throw Error(where(cfg, *n) + ": [fit.parameters] must be a table of NAME = {scale, lower, upper, nominal, estimate}");
      inline_parameters(cfg, *t, "", model_value, inl);
      // TOML tables iterate by key; keep the order of the file.
      std::stable_sort(inl.begin(), inl.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    }
    for (auto& [line, p] : inl) {
      bool replaced = false;
      for (auto& q : table)
        if (q.id == p.id) {
          q = p;
          replaced = true;
        }
      if (!replaced) table.push_back(p);
    }
    spec.parameters = table;
  }
  if (spec.parameters.empty())
    throw Error(cfg.path + ": no fit parameters (give --parameters PARAMS.tsv, fit.parameter_table or [fit.parameters])");
}

namespace {
// Every simulated horizon of the fit (t_end_ms, switch times, the last data sample) within the
// bound of every run (config::kMaxTEndMs).
void check_horizon(const config::Config& cfg, const FitSpec& spec) {
  auto check = [&](double t_ms, const std::string& where, const std::string& what) {
    if (!(t_ms <= config::kMaxTEndMs))
      throw Error(where + ": " + what + " " + std::to_string(t_ms) + " ms is beyond the longest run, " +
                  std::to_string(config::kMaxTEndMs) + " ms (docs/config.md)");
  };
  check(spec.problem.t_end_ms, cfg.path, "[fit] t_end_ms");
  for (const auto& s : spec.targets.switches) check(s.time_ms, cfg.path, "switch time");
  for (const auto& k : spec.targets.kinematics)
    if (!k.data.time_ms.empty()) check(k.data.time_ms.back(), k.file, "the data's last time_ms");
}
}  // namespace

FeatureTarget feature_target(const config::Config& cfg, const toml::table& t) {
  FeatureTarget f;
  f.origin = where(cfg, t);
  const toml::node* nn = t.get("name");
  if (!nn || !t.get("value") || !t.get("tolerance")) throw Error(f.origin + ": [[fit.feature]] needs name, value and tolerance");
  f.feature = text(cfg, *nn, "name");
  f.origin = where(cfg, *nn);
  f.value = number(cfg, *t.get("value"), "value");
  f.tolerance = number(cfg, *t.get("tolerance"), "tolerance");
  return f;
}

FitSpec load_fit_spec(const config::Config& cfg, const model::OdeModel& model, const FitOverrides& ov) {
  FitSpec spec;
  config::SimulationSettings sim = config::simulation_settings(cfg);
  spec.problem.solver = sim.solver;
  const toml::table& fit = fit_section(cfg);
  check_keys(cfg, fit,
             "fit", {"description", "optimizer", "multistart", "sampling", "seed", "threads", "max_iterations",
                     "max_evaluations", "function_tolerance", "parameter_tolerance", "gradient_tolerance", "initial_trust_region_radius", "loss",
                     "loss_scale", "t_end_ms", "discard_ms", "absolute_sigma", "profile", "profile_points",
                     "profile_span", "target_set", "output_dt_ms", "parameter_table", "parameters", "feature",
                     "switch", "data", "recording", "conditions", "petab", "min_swing_deg", "min_swing_fraction", "sensitivity_error_control"});

  load_fit_common(cfg, fit, ov, {"feature", "switch", "recording"},
                  [&](const std::string& name) {
                    for (auto& mp : model.parameters().all())
                      if (parameter_id_matches(name, mp.name)) return mp.value;
                    return 0.0;
                  },
                  spec);
  auto get = [&](const char* k) { return fit.get(k); };

  // Feature targets and switch conditions.
  for (auto* t : fit_tables(cfg, fit, "feature")) {
    check_keys(cfg, *t, "fit.feature", {"name", "value", "tolerance", "set"});
    if (!in_target_set(cfg, *t, spec.target_set)) continue;
    spec.targets.features.push_back(feature_target(cfg, *t));
  }
  for (auto* t : fit_tables(cfg, fit, "switch")) {
    check_keys(cfg, *t, "fit.switch", {"angle", "time_ms", "angle_deg", "angle_tolerance_deg", "velocity_tolerance_deg_s",
                                        "acceleration_tolerance_deg_s2", "set"});
    if (!in_target_set(cfg, *t, spec.target_set)) continue;
    SwitchCondition s;
    s.origin = where(cfg, *t);
    for (const char* req : {"angle", "time_ms", "angle_deg", "angle_tolerance_deg"})
      if (!t->get(req)) throw Error(s.origin + ": [[fit.switch]] needs '" + req + "'");
    s.origin = where(cfg, *t->get("angle"));
    s.channel = text(cfg, *t->get("angle"), "angle");
    s.time_ms = number(cfg, *t->get("time_ms"), "time_ms");
    s.angle_deg = number(cfg, *t->get("angle_deg"), "angle_deg");
    s.angle_tolerance_deg = number(cfg, *t->get("angle_tolerance_deg"), "angle_tolerance_deg");
    if (auto n = t->get("velocity_tolerance_deg_s")) s.velocity_tolerance_deg_s = number(cfg, *n, "velocity_tolerance_deg_s");
    if (auto n = t->get("acceleration_tolerance_deg_s2"))
      s.acceleration_tolerance_deg_s2 = number(cfg, *n, "acceleration_tolerance_deg_s2");
    spec.targets.switches.push_back(s);
  }

  // Kinematic data.
  auto data_tables = fit_tables(cfg, fit, "data");
  if (!ov.data.empty() && data_tables.size() > 1)
    throw Error("--data: the config lists " + std::to_string(data_tables.size()) + " data sets; edit the config instead");
  auto read_data = [&](const toml::table* t, const std::string& file_override) {
    KinematicTarget k;
    std::string file, format = "csv";
    AniposeOptions ap;
    if (t) {
      check_keys(cfg, *t, "fit.data", {"file", "format", "frame_rate_hz", "fnum_offset", "columns", "sigma_deg", "t_min_ms", "time_offset"});
      k.origin = where(cfg, *t);
      if (auto n = t->get("file")) file = resolve_path(cfg, text(cfg, *n, "file"));
      if (auto n = t->get("format")) format = text(cfg, *n, "format");
      if (auto n = t->get("frame_rate_hz")) ap.frame_rate_hz = number(cfg, *n, "frame_rate_hz");
      if (auto n = t->get("fnum_offset")) ap.fnum_offset = number(cfg, *n, "fnum_offset");
      if (auto n = t->get("columns")) {
        auto ct = n->as_table();
        if (!ct) throw Error(where(cfg, *n) + ": columns must be a table { COLUMN = \"<leg>.<joint>\" }");
        for (auto& [col, ch] : *ct) ap.columns[std::string(col.str())] = text(cfg, ch, std::string(col.str()));
      }
      if (auto n = t->get("sigma_deg")) k.sigma_deg = number(cfg, *n, "sigma_deg");
      if (auto n = t->get("t_min_ms")) k.t_min_ms = number(cfg, *n, "t_min_ms");
      if (auto n = t->get("time_offset")) k.time_offset_parameter = text(cfg, *n, "time_offset");
    } else {
      k.origin = "--data";
    }
    if (!file_override.empty()) file = file_override;
    if (!ov.data_format.empty()) format = ov.data_format;
    if (file.empty()) throw Error(k.origin + ": [fit.data] needs file (or give --data)");
    if (format == "csv") k.data = read_kinematic_csv(file);
    else if (format == "anipose") k.data = read_anipose_csv(file, ap);
    else throw Error(k.origin + ": data format must be \"csv\" or \"anipose\", got '" + format + "'");
    spec.inputs.push_back(file);
    k.file = file;
    spec.targets.kinematics.push_back(std::move(k));
  };
  // --data replaces the file of the one [fit.data] or [[fit.recording]] (data first).
  const bool data_to_recording = data_tables.empty() && !fit_tables(cfg, fit, "recording").empty();
  if (!ov.data.empty() && !data_to_recording) read_data(data_tables.empty() ? nullptr : data_tables[0], ov.data);
  else
    for (auto* t : data_tables) read_data(t, "");
  FitOverrides recording_ov = ov;
  if (!data_to_recording) recording_ov.data.clear();
  load_recording_targets(cfg, fit, recording_ov, spec);
  // An estimated noise is the likelihood's own scale; rescaling by 2 cost / (m - n) would count
  // it twice (and the cost then holds the noise residuals' constant).
  for (const auto& t : spec.targets.step_cycles)
    for (const auto& o : t.observables)
      if (!o.sigma_parameter.empty() && !spec.absolute_sigma)
        throw Error(o.origin + ": sigma_deg = \"" + o.sigma_parameter + "\" estimates the noise; set absolute_sigma = true in [fit]");

  // Horizon: [fit] overrides [simulation] for feature targets; kinematic data set their own.
  spec.problem.discard_ms = sim.discard_ms;
  if (auto n = get("discard_ms")) spec.problem.discard_ms = number(cfg, *n, "discard_ms");
  if (auto n = get("t_end_ms")) spec.problem.t_end_ms = number(cfg, *n, "t_end_ms");
  else if (!spec.targets.features.empty() || !spec.targets.step_cycles.empty()) spec.problem.t_end_ms = sim.t_end_ms;
  if (!spec.targets.features.empty() && spec.problem.discard_ms >= spec.problem.t_end_ms)
    throw Error(cfg.path + ": discard_ms must be below t_end_ms for feature targets");
  check_horizon(cfg, spec);
  spec.optimizer.progress_label = "fit";
  if (spec.targets.empty())
    throw Error(cfg.path + ": the fit has no targets (give --data KIN.csv, [[fit.feature]], [[fit.switch]], [fit.data] or [[fit.recording]])");
  return spec;
}

}  // namespace phasmid::fit

namespace phasmid::config {

fit::FitSpec fit_spec(const Config& cfg, const scenario::Scenario& scenario, const fit::FitOverrides& overrides) {
  if (scenario.kind() == "cruse1980") return parse_cruse_fit(cfg, scenario.parameters(), overrides);
  const model::OdeModel* model = scenario.ode_model();
  if (!model) return {};
  fit::FitSpec spec = fit::load_fit_spec(cfg, *model, overrides);
  spec.problem.solver.progress = false;
  return spec;
}

}  // namespace phasmid::config
