#include "config/config.hpp"

#include "common/error.hpp"
#include "config/simulation_table.hpp"
#include "config/model_section.hpp"
#include "config/triggers.hpp"
#include "model/ode_model.hpp"
#include "scenario/ode_scenario.hpp"
#include "scenario/registry.hpp"
#include "solver/integrator_kind.hpp"

namespace phasmid::config {
namespace {

// The [model] table, refusing the pre-registry Cruse form (top-level `model = "..."` and a
// [cruse1980] section) with what to write instead.
const toml::table& model_table(const Config& cfg) {
  if (const toml::node* old = cfg.table.get("model"); old && !old->is_table())
    throw Error(where(cfg, *old) + ": top-level 'model = ...' is no longer read; write [model] with type = " +
                (old->value<std::string>() ? "\"" + *old->value<std::string>() + "\"" : "the model kind") +
                " (docs/config.md)");
  if (const toml::node* old = cfg.table.get("cruse1980"))
    throw Error(where(cfg, *old) + ": the [cruse1980] section is no longer read; put gait and time_stepping into "
                "[model] (type = \"cruse1980\") and the numbers into [parameters] (docs/cruse1980.md)");
  const toml::table* mt = cfg.table["model"].as_table();
  if (!mt) throw Error(cfg.path + ": missing [model] section");
  return *mt;
}

std::unique_ptr<scenario::Scenario> make_from_model_section(const Config& cfg) {
  const toml::table& mt = model_table(cfg);
  const toml::node* type = mt.get("type");
  if (!type) throw Error(where(cfg, mt) + ": [model] needs type = \"...\" (the model kind)");
  const scenario::ModelKind* kind = nullptr;
  try {
    kind = &scenario::model_kind(text(cfg, *type, "type"));
  } catch (const Error& e) {
    throw Error(where(cfg, *type) + ": " + e.what());
  }
  std::set<std::string> keys = kind->keys;
  keys.insert({"type", "description"});
  check_keys(cfg, mt, "model", keys);
  return kind->make(TomlModelSection(cfg, mt));
}

// A [simulation] table of unit = absolute tolerance (atol_by_unit, stiff_part_atol_by_unit).
void unit_tolerances(const Config& cfg, const toml::table& st, const char* key,
                     std::vector<std::pair<std::string, double>>& out) {
  const toml::node* n = st.get(key);
  if (!n) return;
  const toml::table* t = n->as_table();
  if (!t) throw Error(where(cfg, *n) + ": '" + key + "' must be a table of unit = tolerance, e.g. { mV = 1e-4 }");
  out.clear();
  for (const auto& [unit, value] : *t) {
    const double v = number(cfg, value, key);
    if (!(v > 0)) throw Error(where(cfg, value) + ": '" + key + "' tolerances must be > 0");
    out.emplace_back(std::string(unit.str()), v);
  }
}

}  // namespace

std::unique_ptr<scenario::Scenario> build_scenario(const Config& cfg, const std::vector<std::string>& sets) {
  std::unique_ptr<scenario::Scenario> s = make_from_model_section(cfg);
  std::vector<std::string> fixed, overrides;
  if (const toml::table* pt = cfg.table["parameters"].as_table())
    for (auto& [name, node] : flatten(*pt)) {
      s->parameters().set(name, number(cfg, *node, name), where(cfg, *node));
      fixed.push_back(name);
    }
  for (const std::string& a : sets) {
    auto [name, value] = model::parse_assignment(a);
    s->parameters().set(name, value, "--set");
    overrides.push_back(name);
  }
  if (model::OdeModel* m = s->ode_model()) apply_triggers(cfg, *m, fixed, overrides);
  else if (const toml::node* n = cfg.table.get("triggers"))
    throw Error(where(cfg, *n) + ": [[triggers]] apply to ODE models only, not to " + s->kind());
  return s;
}

std::unique_ptr<model::OdeModel> build_model(const Config& cfg, const std::vector<std::string>& sets) {
  std::unique_ptr<scenario::Scenario> s = build_scenario(cfg, sets);
  auto* ode = dynamic_cast<scenario::OdeScenario*>(s.get());
  if (!ode) throw Error(cfg.path + ": model type " + s->kind() + " is not an ODE system");
  return ode->release_model();
}

SimulationSettings simulation_settings(const Config& cfg, const scenario::Scenario* scenario) {
  SimulationSettings s = scenario ? scenario->default_settings() : SimulationSettings{};
  const toml::table* st = cfg.table["simulation"].as_table();
  if (!st) return s;
  return apply_simulation_table(cfg, *st, scenario, s);
}

SimulationSettings apply_simulation_table(const Config& cfg, const toml::table& table, const scenario::Scenario* scenario,
                                          SimulationSettings s) {
  const toml::table* st = &table;
  if (scenario && !scenario->takes_simulation_settings())
    throw Error(where(cfg, *st) + ": [simulation] does not apply to model type " + scenario->kind() +
                " (its own parameters set the run; docs/config.md)");
  check_keys(cfg, *st, "simulation", {"t_end_ms", "output_dt_ms", "discard_ms", "rtol", "atol", "linear_solver", "max_step_ms",
                                              "partitioned", "integrator", "threads", "thread_window_ms", "atol_by_unit",
                                              "stiff_part_tol", "stiff_part_atol_by_unit", "compiled_rhs"});
  auto get = [&](const char* key, double& out, double lo) {
    if (const toml::node* n = st->get(key)) {
      out = number(cfg, *n, key);
      if (!(out > lo)) throw Error(where(cfg, *n) + ": '" + key + "' must be > " + (lo == 0 ? "0" : std::to_string(lo)));
    }
  };
  get("t_end_ms", s.t_end_ms, 0);
  get("output_dt_ms", s.output_dt_ms, 0);
  if (const toml::node* n = st->get("discard_ms")) s.discard_ms = number(cfg, *n, "discard_ms");
  check_run_times(s.t_end_ms, s.output_dt_ms, s.discard_ms, where(cfg, *st) + ": [simulation]");
  get("rtol", s.solver.rtol, 0);
  get("atol", s.solver.atol, 0);
  get("stiff_part_tol", s.solver.stiff_part_tol, 0);
  if (const toml::node* n = st->get("rtol"); n && s.solver.rtol >= 1) throw Error(where(cfg, *n) + ": 'rtol' must be < 1");
  get("max_step_ms", s.solver.max_step_ms, 0);
  if (const toml::node* n = st->get("linear_solver")) {
    std::string v = n->value<std::string>().value_or("");
    if (v == "auto") s.solver.linear_solver = solver::LinearSolverKind::Auto;
    else if (v == "dense") s.solver.linear_solver = solver::LinearSolverKind::Dense;
    else if (v == "band") s.solver.linear_solver = solver::LinearSolverKind::Band;
    else if (v == "klu") s.solver.linear_solver = solver::LinearSolverKind::Klu;
    else throw Error(where(cfg, *n) + ": linear_solver must be \"auto\", \"dense\", \"band\" or \"klu\"");
  }
  if (const toml::node* n = st->get("integrator")) {
    const auto kind = solver::integrator_from_name(n->value<std::string>().value_or(""));
    if (!kind) throw Error(where(cfg, *n) + ": integrator must be one of " + solver::integrator_names());
    s.solver.integrator = *kind;
  }
  if (const toml::node* n = st->get("threads")) {
    const auto v = n->value_exact<int64_t>();
    if (!v || *v < 1 || *v > 64) throw Error(where(cfg, *n) + ": 'threads' must be an integer in 1..64");
    s.solver.threads = static_cast<int>(*v);
  }
  get("thread_window_ms", s.solver.window_ms, 0);
  unit_tolerances(cfg, *st, "atol_by_unit", s.solver.atol_by_unit);
  unit_tolerances(cfg, *st, "stiff_part_atol_by_unit", s.solver.stiff_part_atol_by_unit);
  if (const toml::node* n = st->get("partitioned")) {
    if (n->is_boolean()) {
      s.solver.partitioning = *n->value<bool>() ? solver::Partitioning::On : solver::Partitioning::Off;
    } else if (n->value<std::string>().value_or("") == "auto") {
      s.solver.partitioning = solver::Partitioning::Auto;
    } else if (n->value<std::string>().value_or("") == "neurons") {
      s.solver.partitioning = solver::Partitioning::Neurons;
    } else {
      throw Error(where(cfg, *n) + ": 'partitioned' must be true, false, \"auto\" or \"neurons\"");
    }
    if (s.solver.partitioning == solver::Partitioning::Neurons && s.solver.threads >= 2)
      throw Error(where(cfg, *n) + ": 'partitioned = \"neurons\"' runs on one thread (threads = 1): " +
                  solver::kNeuronsOnOneThread);
  }
  if (const toml::node* n = st->get("compiled_rhs")) {
    if (!n->is_boolean()) throw Error(where(cfg, *n) + ": 'compiled_rhs' must be true or false");
    s.solver.compiled_rhs = *n->value<bool>();
  }
  // A setting that would change nothing is refused rather than ignored.
  if (const toml::node* n = st->get("stiff_part_atol_by_unit");
      n && (s.solver.partitioning != solver::Partitioning::Neurons || !solver::is_explicit_rk(s.solver.integrator)))
    throw Error(where(cfg, *n) + ": 'stiff_part_atol_by_unit' applies only with partitioned = \"neurons\" and an "
                "explicit integrator, whose network parts run CVODES BDF (docs/solver.md \"Integrators\")");
  return s;
}

std::string resolved_config_text(const Config& cfg, const std::vector<std::string>& sets) {
  std::string t = cfg.text;
  if (!sets.empty()) {
    t += "\n# overrides given on the command line (phasmid --set), applied after [parameters]:\n";
    for (auto& s : sets) t += "# --set " + s + "\n";
  }
  return t;
}

}  // namespace phasmid::config
