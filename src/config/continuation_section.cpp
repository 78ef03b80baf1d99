#include "config/continuation_section.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "features/features.hpp"
#include "model/ode_model.hpp"
#include "sensitivity/floquet.hpp"

namespace phasmid::config {
namespace {

// section = "<leg>.liftoff" (beta rising through the leg's ground-contact threshold),
// "<leg>.touchdown" (falling through it) or "angle_max" (the first angle's maxima).
solver::RootSpec named_section(const Config& cfg, const toml::node& node, const model::OdeModel& m,
                               const std::vector<double>& p, const char* key = "section") {
  const std::string s = text(cfg, node, key);
  if (s == "angle_max") return sensitivity::default_section(m);
  const auto dot = s.rfind('.');
  const std::string leg = dot == std::string::npos ? "" : s.substr(0, dot), ev = dot == std::string::npos ? s : s.substr(dot + 1);
  const model::ContactLeg* c = m.contact_leg(leg);
  if (c && (ev == "liftoff" || ev == "touchdown"))
    return {c->beta_state, p[c->threshold_param] * M_PI / 180.0, ev == "liftoff" ? +1 : -1};
  throw Error(where(cfg, node) + ": [continuation] " + key + " '" + s +
              "' is not an event of this model (\"<leg>.liftoff\", \"<leg>.touchdown\" for a leg with ground contact, "
              "\"angle_max\", or give section_state, section_level, section_direction)");
}

int direction(const Config& cfg, const toml::node& node) {
  const std::string d = text(cfg, node, "section_direction");
  if (d == "rising") return +1;
  if (d == "falling") return -1;
  throw Error(where(cfg, node) + ": [continuation] section_direction must be \"rising\" or \"falling\"");
}

void read_range(const Config& cfg, const toml::node& node, continuation::ContinuationOptions& o) {
  const toml::array* a = node.as_array();
  if (!a || a->size() != 2) throw Error(where(cfg, node) + ": [continuation] range must be [start, end]");
  o.start = number(cfg, *a->get(0), "range");
  o.end = number(cfg, *a->get(1), "range");
}

void read_features(const Config& cfg, const toml::node& node, const model::OdeModel& m, continuation::ContinuationOptions& o) {
  const toml::array* a = node.as_array();
  if (!a) throw Error(where(cfg, node) + ": [continuation] features must be a list of feature names");
  std::vector<std::string> known;
  for (const auto& f : features::feature_catalogue(m)) known.push_back(f.name);
  for (const toml::node& e : *a) {
    const std::string name = text(cfg, e, "features");
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      const std::string near = nearest(name, known);
      throw Error(where(cfg, e) + ": [continuation] unknown feature '" + name + "'" +
                  (near.empty() ? "" : " (did you mean '" + near + "'?)"));
    }
    o.features.push_back(name);
  }
}

// held_phases = ["<leg>.liftoff", ...]: events (named as the section is) whose fraction of the
// period, measured on the first cycle, is held along the branch.
void read_held_phases(const Config& cfg, const toml::node& node, const model::OdeModel& m, const std::vector<double>& p,
                      continuation::ContinuationOptions& o) {
  const toml::array* a = node.as_array();
  if (!a) throw Error(where(cfg, node) + ": [continuation] held_phases must be a list of events (\"<leg>.liftoff\", ...)");
  for (const toml::node& e : *a) {
    continuation::HeldPhase h;
    h.name = text(cfg, e, "held_phases");
    if (h.name == "angle_max") throw Error(where(cfg, e) + ": [continuation] held_phases: give a leg's liftoff or touchdown");
    h.event = named_section(cfg, e, m, p, "held_phases");
    o.shooting.held_phases.push_back(h);
  }
}

// [continuation.linked]: "<parameter>" = [value at start, value at end], one per parameter
// moved with the continuation parameter.
void read_linked(const Config& cfg, const toml::node& node, const model::OdeModel& m, continuation::ContinuationOptions& o) {
  const toml::table* t = node.as_table();
  if (!t) throw Error(where(cfg, node) + ": [continuation] linked must be a table of \"<parameter>\" = [from, to]");
  for (const auto& [name, value] : flatten(*t)) {
    if (!m.parameters().contains(name)) {
      const std::string near = nearest(name, m.parameters().names());
      throw Error(where(cfg, *value) + ": [continuation.linked] unknown parameter '" + name + "'" +
                  (near.empty() ? "" : " (did you mean '" + near + "'?)"));
    }
    const toml::array* a = value->as_array();
    if (!a || a->size() != 2) throw Error(where(cfg, *value) + ": [continuation.linked] " + name + " must be [from, to]");
    o.linked.push_back({name, number(cfg, *a->get(0), name), number(cfg, *a->get(1), name)});
  }
}

}  // namespace

continuation::ContinuationOptions continuation_options(const Config& cfg, const model::OdeModel& m,
                                                       const SimulationSettings& sim) {
  const toml::table* t = cfg.table["continuation"].as_table();
  if (!t) throw Error(cfg.path + ": no [continuation] section (it names the parameter and its range)");
  check_keys(cfg, *t, "continuation",
             {"parameter", "range", "initial_step", "min_step", "max_step", "max_points", "section", "section_state",
              "section_level", "section_direction", "transient_ms", "max_period_ms", "tolerance", "max_iterations",
              "residual_rtol", "neutral_tolerance", "held_phases", "features", "feature_cycles", "max_period_factor", "hopf_amplitude_fraction", "locate_iterations", "linked"});
  continuation::ContinuationOptions o;
  o.shooting.solver = sim.solver;
  o.shooting.solver.progress = false;
  const std::vector<double> p = m.parameters().values();
  const toml::node* par = t->get("parameter");
  const toml::node* range = t->get("range");
  if (!par || !range) throw Error(where(cfg, *t) + ": [continuation] needs parameter and range = [start, end]");
  o.parameter = text(cfg, *par, "parameter");
  if (!m.parameters().contains(o.parameter)) {
    const std::string near = nearest(o.parameter, m.parameters().names());
    throw Error(where(cfg, *par) + ": [continuation] unknown parameter '" + o.parameter + "'" +
                (near.empty() ? "" : " (did you mean '" + near + "'?)"));
  }
  read_range(cfg, *range, o);
  // The default (the first joint angle's maxima) only where no section is given: a model
  // without joint angles has none.
  if (auto* n = t->get("section")) o.shooting.section = named_section(cfg, *n, m, p);
  else if (!t->get("section_state")) o.shooting.section = sensitivity::default_section(m);
  if (auto* n = t->get("section_state")) {
    try {
      o.shooting.section.state = m.state_index(text(cfg, *n, "section_state"));
    } catch (const Error& e) {
      throw Error(where(cfg, *n) + ": [continuation] section_state: " + e.what());
    }
  }
  if (auto* n = t->get("section_level")) o.shooting.section.level = number(cfg, *n, "section_level");
  if (auto* n = t->get("section_direction")) o.shooting.section.direction = direction(cfg, *n);
  auto num = [&](const char* key, double& into) {
    if (auto* n = t->get(key)) into = number(cfg, *n, key);
  };
  auto count = [&](const char* key, int& into) {
    if (auto* n = t->get(key)) {
      const double v = number(cfg, *n, key);
      if (!(v >= 1) || v != std::floor(v)) throw Error(where(cfg, *n) + ": [continuation] " + key + " must be a whole number >= 1");
      into = static_cast<int>(v);
    }
  };
  num("initial_step", o.initial_step);
  num("min_step", o.min_step);
  num("max_step", o.max_step);
  num("transient_ms", o.shooting.transient_ms);
  num("max_period_ms", o.shooting.max_period_ms);
  num("tolerance", o.shooting.tolerance);
  num("residual_rtol", o.shooting.residual_rtol);
  num("neutral_tolerance", o.shooting.neutral_tolerance);
  num("feature_cycles", o.feature_cycles);
  num("max_period_factor", o.max_period_factor);
  num("hopf_amplitude_fraction", o.hopf_amplitude_fraction);
  count("max_points", o.max_points);
  count("max_iterations", o.shooting.max_iterations);
  count("locate_iterations", o.locate_iterations);
  if (auto* n = t->get("features")) read_features(cfg, *n, m, o);
  if (auto* n = t->get("linked")) read_linked(cfg, *n, m, o);
  if (auto* n = t->get("held_phases")) read_held_phases(cfg, *n, m, p, o);
  if (!(o.shooting.tolerance > 0) || !(o.shooting.residual_rtol >= 0) ||
      !(o.shooting.neutral_tolerance >= 0 && o.shooting.neutral_tolerance < 1) || !(o.shooting.transient_ms >= 0) || !(o.shooting.max_period_ms > 0) ||
      !(o.feature_cycles >= 2))
    throw Error(where(cfg, *t) + ": [continuation] needs tolerance > 0, 0 <= neutral_tolerance < 1, transient_ms >= 0, max_period_ms > 0, feature_cycles >= 2");
  return o;
}

}  // namespace phasmid::config
