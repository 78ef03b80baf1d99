#include "config/config.hpp"

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "common/embedded.hpp"
#include "common/error.hpp"
#include "config/triggers.hpp"
#include "model/coupled_ctr_fti_model.hpp"
#include "model/mechanical_joint_model.hpp"
#include "model/leg_network.hpp"
#include "model/network_builder.hpp"

namespace phasmid::config {
namespace fs = std::filesystem;

std::string where(const std::string& origin, const toml::node& node) {
  auto line = node.source().begin.line;
  return origin + (line ? ":" + std::to_string(line) : "");
}

std::string where(const Config& cfg, const toml::node& node) { return where(cfg.path, node); }

std::string text(const Config& cfg, const toml::node& node, const std::string& key) {
  if (auto v = node.value<std::string>()) return *v;
  throw Error(where(cfg, node) + ": '" + key + "' must be a string");
}

void check_keys(const Config& cfg, const toml::table& t, const std::string& section,
                const std::set<std::string>& allowed) {
  for (auto& [k, v] : t)
    if (!allowed.count(std::string(k.str()))) {
      std::string list;
      for (auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw Error(where(cfg, v) + ": unknown key '" + std::string(k.str()) + "' in [" + section + "] (allowed: " +
                  list + ")");
    }
}

double number(const Config& cfg, const toml::node& node, const std::string& key) {
  if (auto v = node.value<double>()) return *v;
  throw Error(where(cfg, node) + ": '" + key + "' must be a number");
}

namespace {
std::string text_of(const Config& cfg, const toml::table& t, const std::string& key, const std::string& def) {
  const toml::node* n = t.get(key);
  if (!n) return def;
  if (auto v = n->value<std::string>()) return *v;
  throw Error(where(cfg, *n) + ": '" + key + "' must be a string");
}

// [parameters] accepts quoted dotted names ("middle.fti.b_v" = 12.5) and TOML dotted keys
// (middle.fti.b_v = 12.5, i.e. nested tables); both flatten to the same name.
void flatten(const Config& cfg, const toml::table& t, const std::string& prefix,
             std::vector<std::pair<std::string, const toml::node*>>& out) {
  for (auto& [k, v] : t) {
    std::string name = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (auto sub = v.as_table()) flatten(cfg, *sub, name, out);
    else out.emplace_back(name, &v);
  }
}
}  // namespace

Config parse_config(const std::string& text, const std::string& origin) {
  Config cfg;
  cfg.path = origin;
  cfg.text = text;
  try {
    cfg.table = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    throw Error(origin + ":" + std::to_string(e.source().begin.line) + ": malformed config: " +
                std::string(e.description()));
  }
  return cfg;
}

Config load_config(const std::string& path) {
  if (fs::exists(path)) {
    std::ifstream in(path);
    if (!in) throw Error(path + ": cannot read config");
    std::stringstream ss;
    ss << in.rdbuf();
    return parse_config(ss.str(), path);
  }
  const auto& files = embedded::files();
  for (const std::string& key : {path, "configs/" + path}) {
    auto it = files.find(key);
    if (it != files.end()) return parse_config(it->second, "embedded:" + key);
  }
  throw Error(path + ": no such config file");
}

std::unique_ptr<model::OdeModel> build_model(const Config& cfg, const std::vector<std::string>& sets) {
  const toml::table* mt = cfg.table["model"].as_table();
  if (!mt) throw Error(cfg.path + ": missing [model] section");
  check_keys(cfg, *mt, "model", {"type", "leg", "joint", "start_phase", "thc_table", "description",
                                  "direction_switch", "gait", "coupling", "coupling_strength", "coupling_gate",
                                  "motoneuron", "start_ms"});
  std::string type = text_of(cfg, *mt, "type", "");
  std::string leg = text_of(cfg, *mt, "leg", "middle");
  if (const toml::node* n = mt->get("start_ms"); n && type != "leg")
    throw Error(where(cfg, *n) + ": 'start_ms' applies to type = \"leg\" only (three legs start at their gait's LD start times)");
  std::string thc_table = text_of(cfg, *mt, "thc_table", "");
  if (thc_table != "" && thc_table != "A.16" && thc_table != "A.17")
    throw Error(where(cfg, *mt->get("thc_table")) + ": thc_table must be \"A.16\" or \"A.17\"");
  model::JointType joint;
  try {
    joint = model::parse_joint(text_of(cfg, *mt, "joint", "fti"));
    (void)model::joint_table(leg, joint, thc_table);  // validates the leg
  } catch (const Error& e) {
    throw Error(where(cfg, *mt) + ": " + e.what());
  }

  // Motoneuron formulation of the network models (docs/config.md): "spiking" (default) or "rate".
  model::MotoneuronModel mn = model::MotoneuronModel::Spiking;
  if (const toml::node* n = mt->get("motoneuron")) {
    bool network = type == "single_joint" || type == "leg" || type == "three_legs" || type == "curve_walking";
    if (!network) throw Error(where(cfg, *n) + ": 'motoneuron' applies to network models only (single_joint, leg, three_legs, curve_walking)");
    try {
      mn = model::parse_motoneuron_model(text_of(cfg, *mt, "motoneuron", "spiking"));
    } catch (const Error& e) {
      throw Error(where(cfg, *n) + ": " + e.what());
    }
  }

  std::unique_ptr<model::OdeModel> m;
  if (type == "mechanical_joint") {
    model::JointNaming n = model::joint_naming(joint);
    model::JointTable t = model::joint_table(leg, joint, thc_table);
    // Section 3.1.1: period 500 ms; phase relations FE 1:1, PR 1:3 (retraction 125 ms),
    // LD 3:5 (levation 188 ms); each joint starts at rest at the extremal angle of its first phase.
    std::string start = text_of(cfg, *mt, "start_phase", n.phase_inc);
    if (start != n.phase_inc && start != n.phase_dec)
      throw Error(where(cfg, *mt->get("start_phase")) + ": start_phase must be '" + n.phase_inc + "' or '" +
                  n.phase_dec + "'");
    bool inc = start == n.phase_inc;
    double inc_ms = joint == model::JointType::Fti ? 250 : joint == model::JointType::Ctr ? 188 : 125;
    double first = inc ? inc_ms : 500 - inc_ms;
    double angle0 = inc ? t.angle_min_deg : t.angle_max_deg;
    m = std::make_unique<model::MechanicalJointModel>(leg, joint, inc, first, 500, angle0, thc_table);
  } else if (type == "coupled_ctr_fti") {
    m = std::make_unique<model::CoupledCtrFtiModel>(leg);
  } else if (type == "single_joint") {
    m = model::build_single_joint_model(leg, joint, thc_table, mn);
  } else if (type == "curve_walking") {
    m = model::build_curve_walking_model(mn);
  } else if (type == "leg" || type == "three_legs") {
    bool sw = false;
    if (const toml::node* n = mt->get("direction_switch")) {
      if (auto v = n->value<bool>()) sw = *v;
      else throw Error(where(cfg, *n) + ": 'direction_switch' must be true or false");
    }
    if (type == "leg") {
      model::LegOptions o;
      o.thc_set = thc_table;
      o.direction_switch = sw;
      o.motoneuron = mn;
      if (const toml::node* n = mt->get("start_ms")) {
        // The single leg's start time (docs/walking_model.md, "Start time of a single leg"):
        // held in stance with both PR CPGs silent until then, as each leg of curve walking.
        auto v = n->value<double>();
        if (!v || *v < 0) throw Error(where(cfg, *n) + ": 'start_ms' must be a number >= 0 (ms)");
        o.ld_release_ms = *v;
        o.ld_release_source = "config start_ms (a choice: the seeds give no start phase of the single leg)";
        o.ld_hold_g_pr = 5.0;
        o.ld_hold_g_pr_source = "choice: PR silent until the start time, as in curve walking (Section 2.5.3: the PR is a reflex chain)";
      }
      m = model::build_leg_model(leg, o);
    } else {
      model::ThreeLegOptions o;
      o.direction_switch = sw;
      o.motoneuron = mn;
      o.gait = text_of(cfg, *mt, "gait", "tetrapod");
      std::string strength = text_of(cfg, *mt, "coupling_strength", "weak");
      if (strength != "weak" && strength != "strong")
        throw Error(where(cfg, *mt->get("coupling_strength")) + ": coupling_strength must be \"weak\" or \"strong\"");
      o.strong = strength == "strong";
      try {
        model::set_coupling_variant(o, text_of(cfg, *mt, "coupling", "inhibitory"));
      } catch (const Error& e) {
        throw Error(where(cfg, mt->get("coupling") ? *mt->get("coupling") : *mt) + ": " + e.what());
      }
      try {
        model::set_coupling_gate(o, text_of(cfg, *mt, "coupling_gate", "target_swing"));
      } catch (const Error& e) {
        throw Error(where(cfg, *mt->get("coupling_gate")) + ": " + e.what());
      }
      try {
        m = model::build_three_leg_model(o);
      } catch (const Error& e) {
        throw Error(where(cfg, mt->get("gait") ? *mt->get("gait") : *mt) + ": " + e.what());
      }
    }
  } else {
    const toml::node* n = mt->get("type");
    throw Error((n ? where(cfg, *n) : cfg.path) + ": unknown model type '" + type +
                "' (expected mechanical_joint, coupled_ctr_fti, single_joint, leg, three_legs or curve_walking)");
  }

  std::vector<std::string> fixed, overrides;
  if (const toml::table* pt = cfg.table["parameters"].as_table()) {
    std::vector<std::pair<std::string, const toml::node*>> entries;
    flatten(cfg, *pt, "", entries);
    for (auto& [name, node] : entries) {
      m->parameters().set(name, number(cfg, *node, name), where(cfg, *node));
      fixed.push_back(name);
    }
  }
  for (const std::string& s : sets) {
    auto [name, value] = model::parse_assignment(s);
    m->parameters().set(name, value, "--set");
    overrides.push_back(name);
  }
  apply_triggers(cfg, *m, fixed, overrides);
  return m;
}

SimulationSettings simulation_settings(const Config& cfg) {
  SimulationSettings s;
  const toml::table* st = cfg.table["simulation"].as_table();
  if (!st) return s;
  check_keys(cfg, *st, "simulation", {"t_end_ms", "output_dt_ms", "discard_ms", "rtol", "atol", "linear_solver", "max_step_ms",
                                              "partitioned"});
  auto get = [&](const char* key, double& out, double lo) {
    if (const toml::node* n = st->get(key)) {
      out = number(cfg, *n, key);
      if (!(out > lo)) throw Error(where(cfg, *n) + ": '" + key + "' must be > " + std::to_string(lo));
    }
  };
  get("t_end_ms", s.t_end_ms, 0);
  get("output_dt_ms", s.output_dt_ms, 0);
  if (const toml::node* n = st->get("discard_ms")) {
    s.discard_ms = number(cfg, *n, "discard_ms");
    if (s.discard_ms < 0 || s.discard_ms >= s.t_end_ms)
      throw Error(where(cfg, *n) + ": 'discard_ms' must be in [0, t_end_ms)");
  }
  get("rtol", s.solver.rtol, 0);
  get("atol", s.solver.atol, 0);
  get("max_step_ms", s.solver.max_step_ms, 0);
  if (const toml::node* n = st->get("linear_solver")) {
    std::string v = n->value<std::string>().value_or("");
    if (v == "auto") s.solver.linear_solver = solver::LinearSolverKind::Auto;
    else if (v == "dense") s.solver.linear_solver = solver::LinearSolverKind::Dense;
    else if (v == "band") s.solver.linear_solver = solver::LinearSolverKind::Band;
    else if (v == "klu") s.solver.linear_solver = solver::LinearSolverKind::Klu;
    else throw Error(where(cfg, *n) + ": linear_solver must be \"auto\", \"dense\", \"band\" or \"klu\"");
  }
  if (const toml::node* n = st->get("partitioned")) {
    if (n->is_boolean()) {
      s.solver.partitioning = *n->value<bool>() ? solver::Partitioning::On : solver::Partitioning::Off;
    } else if (n->value<std::string>().value_or("") == "auto") {
      s.solver.partitioning = solver::Partitioning::Auto;
    } else {
      throw Error(where(cfg, *n) + ": 'partitioned' must be true, false or \"auto\"");
    }
  }
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
