#include "config/simulation_table.hpp"

#include <array>
#include <map>

#include "common/error.hpp"
#include "scenario/kinds/integration.hpp"

namespace phasmid::config {
namespace {

// Keys of earlier versions: where each went, for a one-line error that says what to write.
const std::map<std::string, std::string>& moved_keys() {
  static const std::map<std::string, std::string> m = {
      {"partitioned", "[simulation.expert] partitioning = \"whole\" | \"joints\" | \"neurons\""},
      {"linear_solver", "[simulation.expert] linear_solver"},
      {"threads", "[simulation.expert] threads"},
      {"thread_window_ms", "[simulation.expert] window_ms"},
      {"compiled_rhs", "[simulation.expert] compiled_rhs"},
      {"stiff_part_tol", "[simulation.expert] network_tol"},
      {"stiff_part_atol_by_unit", "[simulation.expert] network_atol_by_unit"},
      {"atol_by_unit", "[simulation.expert] atol_by_unit"}};
  return m;
}

// Refuses keys of earlier versions by name (what to write instead), then any other unknown key.
void check_simulation_keys(const Config& cfg, const toml::table& st) {
  for (const auto& [k, v] : st)
    if (auto it = moved_keys().find(std::string(k.str())); it != moved_keys().end())
      throw Error(where(cfg, v) + ": '" + it->first + "' is no longer a [simulation] key; the model kind chooses it "
                  "(docs/solver.md), or set " + it->second + " (docs/config.md)");
  check_keys(cfg, st, "simulation", simulation_keys());
}

std::optional<double> positive(const Config& cfg, const toml::table& t, const char* key) {
  const toml::node* n = t.get(key);
  if (!n) return std::nullopt;
  const double v = number(cfg, *n, key);
  if (!(v > 0)) throw Error(where(cfg, *n) + ": '" + key + "' must be > 0");
  return v;
}

// A table of unit = absolute tolerance (atol_by_unit, network_atol_by_unit).
std::optional<std::vector<std::pair<std::string, double>>> unit_tolerances(const Config& cfg, const toml::table& t,
                                                                           const char* key) {
  const toml::node* n = t.get(key);
  if (!n) return std::nullopt;
  const toml::table* u = n->as_table();
  if (!u) throw Error(where(cfg, *n) + ": '" + key + "' must be a table of unit = tolerance, e.g. { mV = 1e-4 }");
  std::vector<std::pair<std::string, double>> out;
  for (const auto& [unit, value] : *u) {
    const double v = number(cfg, value, key);
    if (!(v > 0)) throw Error(where(cfg, value) + ": '" + key + "' tolerances must be > 0");
    out.emplace_back(std::string(unit.str()), v);
  }
  return out;
}

// One of `names` (a string key), as its index.
std::optional<size_t> choice(const Config& cfg, const toml::table& t, const char* key,
                             const std::vector<std::string>& names, const std::string& note = "") {
  const toml::node* n = t.get(key);
  if (!n) return std::nullopt;
  const std::string v = n->value<std::string>().value_or("");
  for (size_t i = 0; i < names.size(); ++i)
    if (v == names[i]) return i;
  std::string list;
  for (size_t i = 0; i < names.size(); ++i)
    list += (i == 0 ? "\"" : i + 1 == names.size() ? " or \"" : ", \"") + names[i] + "\"";
  throw Error(where(cfg, *n) + ": '" + key + "' must be " + list + note);
}

void read_expert(const Config& cfg, const toml::table& et, scenario::IntegrationRequest& r) {
  check_keys(cfg, et, "simulation.expert", expert_keys());
  if (auto i = choice(cfg, et, "partitioning", {"whole", "joints", "neurons"}))
    r.partitioning = std::array{solver::Partitioning::Off, solver::Partitioning::On, solver::Partitioning::Neurons}[*i];
  if (const toml::node* n = et.get("threads")) {
    const auto v = n->value_exact<int64_t>();
    if (!v || *v < 1 || *v > 64) throw Error(where(cfg, *n) + ": 'threads' must be an integer in 1..64");
    r.threads = static_cast<int>(*v);
  }
  if (auto v = positive(cfg, et, "window_ms")) r.window_ms = v;
  if (const toml::node* n = et.get("compiled_rhs")) {
    if (!n->is_boolean()) throw Error(where(cfg, *n) + ": 'compiled_rhs' must be true or false");
    r.compiled_rhs = *n->value<bool>();
  }
  if (auto i = choice(cfg, et, "linear_solver", {"auto", "dense", "band", "klu"}))
    r.linear_solver = std::array{solver::LinearSolverKind::Auto, solver::LinearSolverKind::Dense,
                                 solver::LinearSolverKind::Band, solver::LinearSolverKind::Klu}[*i];
  if (auto v = positive(cfg, et, "network_tol")) r.network_tol = v;
  if (auto v = unit_tolerances(cfg, et, "atol_by_unit")) r.atol_by_unit = v;
  if (auto v = unit_tolerances(cfg, et, "network_atol_by_unit")) r.network_atol_by_unit = v;
}

}  // namespace

const std::set<std::string>& simulation_keys() {
  static const std::set<std::string> k = {"t_end_ms", "output_dt_ms", "discard_ms", "rtol",
                                          "atol",     "max_step_ms",  "integrator", "expert"};
  return k;
}

const std::set<std::string>& expert_keys() {
  static const std::set<std::string> k = {"partitioning", "threads",      "window_ms",    "compiled_rhs",
                                          "linear_solver", "network_tol", "atol_by_unit", "network_atol_by_unit"};
  return k;
}

SimulationRequest read_simulation_table(const Config& cfg, const toml::table& st, const scenario::Scenario* scenario,
                                        SimulationRequest r) {
  if (scenario && !scenario->takes_simulation_settings())
    throw Error(where(cfg, st) + ": [simulation] does not apply to model type " + scenario->kind() +
                " (its own parameters set the run; docs/config.md)");
  check_simulation_keys(cfg, st);
  if (auto v = positive(cfg, st, "t_end_ms")) r.t_end_ms = v;
  if (auto v = positive(cfg, st, "output_dt_ms")) r.output_dt_ms = v;
  if (const toml::node* n = st.get("discard_ms")) r.discard_ms = number(cfg, *n, "discard_ms");
  scenario::IntegrationRequest& g = r.integration;
  if (auto v = positive(cfg, st, "rtol")) {
    if (*v >= 1) throw Error(where(cfg, *st.get("rtol")) + ": 'rtol' must be < 1");
    g.rtol = v;
  }
  if (auto v = positive(cfg, st, "atol")) g.atol = v;
  if (auto v = positive(cfg, st, "max_step_ms")) g.max_step_ms = v;
  if (auto i = choice(cfg, st, "integrator", {"auto", "cvodes_bdf", "dopri5"},
                      " (\"auto\": the model kind's choice, docs/solver.md)"))
    g.integrator = *i == 0   ? std::nullopt
                   : *i == 1 ? std::optional(solver::IntegratorKind::Bdf)
                             : std::optional(solver::IntegratorKind::Dopri5);
  if (const toml::node* n = st.get("expert")) {
    const toml::table* et = n->as_table();
    if (!et) throw Error(where(cfg, *n) + ": 'expert' must be the table [simulation.expert]");
    read_expert(cfg, *et, g);
  }
  return r;
}

SimulationRequest simulation_request(const Config& cfg, const scenario::Scenario* scenario) {
  const toml::table* st = cfg.table["simulation"].as_table();
  return st ? read_simulation_table(cfg, *st, scenario, {}) : SimulationRequest{};
}

SimulationSettings resolve_simulation(const SimulationRequest& r, const scenario::Scenario* scenario,
                                      const std::string& where) {
  SimulationSettings s;
  s.t_end_ms = r.t_end_ms.value_or(s.t_end_ms);
  s.output_dt_ms = r.output_dt_ms.value_or(s.output_dt_ms);
  s.discard_ms = r.discard_ms.value_or(s.discard_ms);
  check_run_times(s.t_end_ms, s.output_dt_ms, s.discard_ms, where);
  try {
    s.solver = scenario ? scenario->integration(r.integration) : scenario::kinds::whole_system_bdf()(r.integration);
    s.solver.validate();  // the one check every caller shares (solver/solver_options.hpp)
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
  return s;
}

}  // namespace phasmid::config
