#include "config/config.hpp"

#include "common/error.hpp"
#include "config/simulation_table.hpp"
#include "config/model_section.hpp"
#include "config/triggers.hpp"
#include "model/ode_model.hpp"
#include "scenario/ode_scenario.hpp"
#include "scenario/registry.hpp"

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

namespace {
std::string simulation_where(const Config& cfg) {
  const toml::node* st = cfg.table.get("simulation");
  return st ? where(cfg, *st) + ": [simulation]" : cfg.path;
}
}  // namespace

SimulationSettings simulation_settings(const Config& cfg, const scenario::Scenario* scenario) {
  return resolve_simulation(simulation_request(cfg, scenario), scenario, simulation_where(cfg));
}

SimulationSettings bdf_simulation_settings(const Config& cfg, const scenario::Scenario* scenario) {
  SimulationRequest r = simulation_request(cfg, scenario);
  if (!r.integration.integrator) r.integration.integrator = solver::IntegratorKind::Bdf;
  return resolve_simulation(r, scenario, simulation_where(cfg));
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
