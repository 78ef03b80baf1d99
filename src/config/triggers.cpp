#include "config/triggers.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "common/units.hpp"

namespace phasmid::config {
namespace {

// A command time is a parameter the model turns into a breakpoint (a central command switched
// on at that time): probed by moving it to an otherwise unused time.
bool is_command_time(const model::OdeModel& m, size_t k) {
  std::vector<double> p = m.parameters().values();
  const double probe_ms = 12345.678;
  p[k] = probe_ms;
  for (double b : m.breakpoints(p, 1e12))
    if (std::abs(b - probe_ms) < 1e-9) return true;
  return false;
}

std::vector<std::string> names_of(const Config& cfg, const toml::node& node, const std::string& key) {
  std::vector<std::string> out;
  if (auto s = node.value<std::string>()) out.push_back(*s);
  else if (auto a = node.as_array()) {
    for (const toml::node& x : *a) out.push_back(text(cfg, x, key));
  } else
    throw Error(where(cfg, node) + ": '" + key + "' must be a parameter name or an array of names");
  if (out.empty()) throw Error(where(cfg, node) + ": '" + key + "' names no parameter");
  return out;
}

// Legs with ground contact: a CTr angle and a PR threshold <leg>.coupling.beta_thr_pr (the
// legs of features::feature_roots), listed for messages.
bool has_contact(const model::OdeModel& m, const std::string& leg) {
  return !leg.empty() && m.parameters().contains(leg + ".coupling.beta_thr_pr");
}

std::string contact_legs(const model::OdeModel& m) {
  std::string legs;
  for (const auto& ch : m.angles())
    if (ch.joint == "ctr" && has_contact(m, ch.leg)) legs += (legs.empty() ? "" : ", ") + ch.leg;
  return legs;
}

// "<leg>.touchdown" (beta falling through <leg>.coupling.beta_thr_pr) or "<leg>.liftoff"
// (rising): the ground-contact events of the walking models (features::feature_roots).
// Returns the event's leg.
std::string parse_event(const Config& cfg, const toml::node& node, const model::OdeModel& m, model::CommandTrigger& tr) {
  tr.event = text(cfg, node, "event");
  const size_t dot = tr.event.rfind('.');
  const std::string leg = dot == std::string::npos ? "" : tr.event.substr(0, dot);
  const std::string kind = dot == std::string::npos ? tr.event : tr.event.substr(dot + 1);
  const std::string legs = contact_legs(m);
  if (!has_contact(m, leg) || (kind != "touchdown" && kind != "liftoff"))
    throw Error(where(cfg, node) + ": unknown event '" + tr.event + "' in [[triggers]] (expected <leg>.touchdown or <leg>.liftoff" +
                (legs.empty() ? "; this model has no legs with ground contact)" : " with leg one of " + legs + ")"));
  tr.state = m.state_index(leg + ".ctr.beta");
  tr.level_param = m.parameters().index(leg + ".coupling.beta_thr_pr");
  tr.level_scale = units::kRadPerDeg;  // threshold in deg, beta integrated in rad
  tr.direction = kind == "liftoff" ? +1 : -1;
  return leg;
}

// in_stance = ["hind", ...]: legs (other than the event's own) that must be in stance at the
// event, on the touched-down side of the threshold of their <leg>.touchdown event.
void parse_in_stance(const Config& cfg, const toml::node& node, const model::OdeModel& m, const std::string& event_leg,
                     model::CommandTrigger& tr) {
  const toml::array* a = node.as_array();
  if (!a) throw Error(where(cfg, node) + ": 'in_stance' must be an array of leg names, e.g. in_stance = [\"hind\"]");
  if (a->empty()) throw Error(where(cfg, node) + ": 'in_stance' names no leg");
  const std::string legs = contact_legs(m);
  for (const toml::node& x : *a) {
    auto leg = x.value<std::string>();
    if (!leg) throw Error(where(cfg, x) + ": 'in_stance' must be an array of leg names, e.g. in_stance = [\"hind\"]");
    if (!has_contact(m, *leg))
      throw Error(where(cfg, x) + ": unknown leg '" + *leg + "' in [[triggers]] 'in_stance' (" +
                  (legs.empty() ? "this model has no legs with ground contact)" : "expected one of " + legs + ")"));
    if (*leg == event_leg)
      throw Error(where(cfg, x) + ": leg '" + *leg + "' in 'in_stance' is the leg of the event " + tr.event +
                  " (name the other legs that must be in stance)");
    for (const auto& c : tr.in_stance)
      if (c.leg == *leg) throw Error(where(cfg, x) + ": leg '" + *leg + "' is named twice in 'in_stance'");
    model::StanceCondition c;
    c.leg = *leg;
    c.state = m.state_index(*leg + ".ctr.beta");
    c.level_param = m.parameters().index(*leg + ".coupling.beta_thr_pr");
    c.level_scale = units::kRadPerDeg;
    c.stance_side = -1;  // the direction of <leg>.touchdown: beta below the threshold
    tr.in_stance.push_back(std::move(c));
  }
}

double non_negative(const Config& cfg, const toml::node& node, const std::string& key) {
  double v = number(cfg, node, key);
  if (!(v >= 0)) throw Error(where(cfg, node) + ": '" + key + "' must be >= 0");
  return v;
}
}  // namespace

void apply_triggers(const Config& cfg, model::OdeModel& m, const std::vector<std::string>& fixed,
                    const std::vector<std::string>& overrides) {
  const toml::node* root = cfg.table.get("triggers");
  if (!root) return;
  const toml::array* arr = root->as_array();
  if (!arr || !arr->is_array_of_tables())
    throw Error(where(cfg, *root) + ": 'triggers' must be an array of tables: write each as [[triggers]]");
  std::vector<model::CommandTrigger> out;
  std::vector<std::string> targeted;
  for (const toml::node& item : *arr) {
    const toml::table& t = *item.as_table();
    check_keys(cfg, t, "[triggers]", {"set", "event", "in_stance", "after", "after_ms", "delay_ms", "occurrence", "debounce_ms"});
    model::CommandTrigger tr;
    const toml::node* set = t.get("set");
    const toml::node* event = t.get("event");
    if (!set || !event)
      throw Error(where(cfg, item) + ": a [[triggers]] entry needs 'set' (command-time parameters) and 'event'");
    for (const std::string& name : names_of(cfg, *set, "set")) {
      if (!m.parameters().contains(name))
        throw Error(where(cfg, *set) + ": unknown parameter '" + name + "' in [[triggers]] 'set'");
      const size_t k = m.parameters().index(name);
      if (!is_command_time(m, k))
        throw Error(where(cfg, *set) + ": '" + name + "' is not a command time (a parameter that switches a command on at a time, unit ms)");
      if (std::count(fixed.begin(), fixed.end(), name))
        throw Error(where(cfg, *set) + ": '" + name + "' is set both in [parameters] and by a trigger");
      if (std::count(targeted.begin(), targeted.end(), name))
        throw Error(where(cfg, *set) + ": '" + name + "' is set by two triggers");
      targeted.push_back(name);
      // An explicit --set gives a fixed time, which replaces the trigger for this parameter.
      if (!std::count(overrides.begin(), overrides.end(), name)) tr.targets.push_back(k);
    }
    const std::string event_leg = parse_event(cfg, *event, m, tr);
    if (const toml::node* n = t.get("in_stance")) parse_in_stance(cfg, *n, m, event_leg, tr);
    const toml::node* after = t.get("after");
    const toml::node* after_ms = t.get("after_ms");
    if (after && after_ms)
      throw Error(where(cfg, *after) + ": give either 'after' (a parameter) or 'after_ms' in a [[triggers]] entry, not both");
    if (after) {
      const std::string name = text(cfg, *after, "after");
      if (!m.parameters().contains(name))
        throw Error(where(cfg, *after) + ": unknown parameter '" + name + "' in [[triggers]] 'after'");
      tr.after_param = m.parameters().index(name);
    }
    if (after_ms) tr.after_ms = non_negative(cfg, *after_ms, "after_ms");
    if (const toml::node* n = t.get("delay_ms")) tr.delay_ms = non_negative(cfg, *n, "delay_ms");
    if (const toml::node* n = t.get("debounce_ms")) tr.debounce_ms = non_negative(cfg, *n, "debounce_ms");
    if (const toml::node* n = t.get("occurrence")) {
      auto v = n->value<int64_t>();
      if (!v || *v < 1) throw Error(where(cfg, *n) + ": 'occurrence' must be an integer >= 1");
      tr.occurrence = static_cast<int>(*v);
    }
    if (!tr.targets.empty()) out.push_back(std::move(tr));
  }
  m.set_triggers(std::move(out));
}

}  // namespace phasmid::config
