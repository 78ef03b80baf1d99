#include "config/continuation_section.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/error.hpp"
#include "features/features.hpp"
#include "model/ode_model.hpp"
#include "sensitivity/floquet.hpp"

namespace phasmid::config {
namespace {

std::string g(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

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
  if (o.start == o.end) throw Error(where(cfg, node) + ": [continuation] range must have two different values");
}

// A value the parameter may take (model::Parameter's admissible range), or file:line.
void check_admissible(const Config& cfg, const toml::node& node, const model::Parameter& p, double v) {
  if (v < p.lower || v > p.upper)
    throw Error(where(cfg, node) + ": [continuation] impossible value " + g(v) + " for parameter '" + p.name +
                "' (allowed range [" + g(p.lower) + ", " + g(p.upper) + "] " + p.unit + ")");
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
    if (std::find(o.features.begin(), o.features.end(), name) != o.features.end())
      throw Error(where(cfg, e) + ": [continuation] feature '" + name + "' listed twice");
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
    for (const continuation::HeldPhase& other : o.shooting.held_phases)
      if (other.name == h.name) throw Error(where(cfg, e) + ": [continuation] held phase '" + h.name + "' listed twice");
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
    if (name == o.parameter)
      throw Error(where(cfg, *value) + ": [continuation.linked] '" + name + "' is the continued parameter (its range is [continuation] range)");
    for (const auto& l : o.linked)
      if (l.name == name) throw Error(where(cfg, *value) + ": [continuation.linked] '" + name + "' given twice");
    const toml::array* a = value->as_array();
    if (!a || a->size() != 2) throw Error(where(cfg, *value) + ": [continuation.linked] " + name + " must be [from, to]");
    const model::Parameter& p = m.parameters().at(name);
    for (const toml::node& e : *a) check_admissible(cfg, e, p, number(cfg, e, name));
    o.linked.push_back({name, number(cfg, *a->get(0), name), number(cfg, *a->get(1), name)});
  }
}

// "file:line: [continuation] KEY = V must be in (lo, hi]" and the like: every number of the
// section is bounded, so that no value wraps, ends a correct branch at once or runs without end.
struct Bounds {
  double lo, hi;
  bool lo_open = false, hi_open = false;
};

double bounded(const Config& cfg, const toml::node& n, const char* key, Bounds b, bool whole = false) {
  const double v = number(cfg, n, key);
  const bool ok = (b.lo_open ? v > b.lo : v >= b.lo) && (b.hi_open ? v < b.hi : v <= b.hi);
  if (!ok || (whole && v != std::floor(v)))
    throw Error(where(cfg, n) + ": [continuation] " + key + " = " + g(v) + " must be " + (whole ? "a whole number " : "") +
                "in " + (b.lo_open ? "(" : "[") + g(b.lo) + ", " + g(b.hi) + (b.hi_open ? ")" : "]"));
  return v;
}

// Bounds of the counts and durations (docs/continuation.md, "Limits"). Durations share the
// run-time bound of every run (config::kMaxTEndMs); the longest features run of a point is
// feature_cycles x max_period_factor x max_period_ms, bounded alike.
constexpr double kMaxPoints = 100000, kMaxIterations = 1000, kMaxFeatureCycles = 1000, kMaxPeriodFactor = 1000;

void read_numbers(const Config& cfg, const toml::table& t, continuation::ContinuationOptions& o) {
  auto num = [&](const char* key, double& into, Bounds b) {
    if (auto* n = t.get(key)) into = bounded(cfg, *n, key, b);
  };
  auto count = [&](const char* key, int& into, double lo, double hi) {
    if (auto* n = t.get(key)) into = static_cast<int>(bounded(cfg, *n, key, {lo, hi}, true));
  };
  const double inf = std::numeric_limits<double>::infinity();
  // A step left out takes its default (continuation.hpp); one given must be positive.
  num("initial_step", o.initial_step, {0, inf, true, true});
  num("min_step", o.min_step, {0, inf, true, true});
  num("max_step", o.max_step, {0, inf, true, true});
  num("transient_ms", o.shooting.transient_ms, {0, kMaxTEndMs});
  num("max_period_ms", o.shooting.max_period_ms, {0, kMaxTEndMs, true});
  num("tolerance", o.shooting.tolerance, {0, inf, true, true});
  num("residual_rtol", o.shooting.residual_rtol, {0, 1, false, true});
  num("neutral_tolerance", o.shooting.neutral_tolerance, {0, 1, false, true});
  // A factor <= 1 or a fraction >= 1 would end a correct branch at its first points.
  num("max_period_factor", o.max_period_factor, {1, kMaxPeriodFactor, true});
  num("hopf_amplitude_fraction", o.hopf_amplitude_fraction, {0, 1, false, true});
  if (auto* n = t.get("feature_cycles")) o.feature_cycles = bounded(cfg, *n, "feature_cycles", {2, kMaxFeatureCycles}, true);
  count("max_points", o.max_points, 2, kMaxPoints);
  count("max_iterations", o.shooting.max_iterations, 1, kMaxIterations);
  count("locate_iterations", o.locate_iterations, 1, kMaxIterations);
  const double longest = o.feature_cycles * o.max_period_factor * o.shooting.max_period_ms;
  if (longest > kMaxTEndMs) {
    const char* key = t.get("feature_cycles") ? "feature_cycles" : t.get("max_period_factor") ? "max_period_factor" : "max_period_ms";
    throw Error(where(cfg, *t.get(key)) + ": [continuation] feature_cycles x max_period_factor x max_period_ms = " + g(longest) +
                " ms must be at most " + g(kMaxTEndMs) + " ms (the longest features run of a point)");
  }
}

// min_step <= initial_step <= max_step, with the defaults of the ones left out.
void check_steps(const Config& cfg, const toml::table& t, const continuation::ContinuationOptions& o) {
  continuation::ContinuationOptions d = o;
  continuation::fill_default_steps(d);
  if (d.min_step <= d.initial_step && d.initial_step <= d.max_step) return;
  const toml::node* n = t.get("initial_step") ? t.get("initial_step") : t.get("min_step") ? t.get("min_step") : t.get("max_step");
  throw Error(where(cfg, n ? *n : static_cast<const toml::node&>(t)) + ": [continuation] needs min_step (" + g(d.min_step) +
              ") <= initial_step (" + g(d.initial_step) + ") <= max_step (" + g(d.max_step) +
              "); the defaults: min_step = |range|/1e5, initial_step = |range|/50, max_step = |range|/10");
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
  for (const toml::node& e : *range->as_array())
    check_admissible(cfg, e, m.parameters().at(o.parameter), number(cfg, e, "range"));
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
  read_numbers(cfg, *t, o);
  if (auto* n = t->get("features")) read_features(cfg, *n, m, o);
  if (auto* n = t->get("linked")) read_linked(cfg, *n, m, o);
  if (auto* n = t->get("held_phases")) read_held_phases(cfg, *n, m, p, o);
  check_steps(cfg, *t, o);
  return o;
}

}  // namespace phasmid::config
