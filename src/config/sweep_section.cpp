#include "config/sweep_section.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "common/error.hpp"
#include "sweep/design.hpp"

namespace phasmid::sweep {
using config::number;
using config::where;
using config::check_keys;


namespace {
constexpr std::size_t kMaxPoints = 10'000'000;

std::size_t positive_count(const config::Config& cfg, const toml::node& n, const std::string& key) {
  auto v = n.value_exact<int64_t>();
  if (!v || *v < 1) throw Error(where(cfg, n) + ": '" + key + "' must be a positive integer");
  if (static_cast<std::size_t>(*v) > kMaxPoints)
    throw Error(where(cfg, n) + ": '" + key + "' is too large (at most " + std::to_string(kMaxPoints) + ")");
  return static_cast<std::size_t>(*v);
}

void check_admissible(const config::Config& cfg, const toml::node& n, const model::Parameter& p, double v) {
  if (!std::isfinite(v) || v < p.lower || v > p.upper) {
    std::ostringstream os;
    os << where(cfg, n) << ": impossible value " << v << " for parameter '" << p.name << "' (allowed range ["
       << p.lower << ", " << p.upper << "] " << p.unit << ")";
    throw Error(os.str());
  }
}

void parse_options(const config::Config& cfg, const toml::table& st, SweepSpec& spec) {
  const toml::node* on = st.get("option");
  if (!on) return;
  const toml::array* arr = on->as_array();
  if (!arr || arr->empty() || !arr->is_array_of_tables())
    throw Error(where(cfg, *on) + ": 'sweep.option' must be an array of tables ([[sweep.option]])");
  std::set<std::string> seen;
  for (const toml::node& el : *arr) {
    const toml::table& t = *el.as_table();
    check_keys(cfg, t, "[sweep.option]", {"name", "values"});
    const toml::node* name = t.get("name");
    if (!name || !name->is_string()) throw Error(where(cfg, el) + ": [[sweep.option]] needs name = \"<[model] key>\"");
    SweptOption o;
    o.name = *name->value<std::string>();
    if (o.name == "type") throw Error(where(cfg, *name) + ": the model type cannot be swept (one model kind per sweep)");
    if (!seen.insert(o.name).second) throw Error(where(cfg, *name) + ": option '" + o.name + "' swept twice");
    const toml::node* values = t.get("values");
    const toml::array* va = values ? values->as_array() : nullptr;
    if (!va || va->empty())
      throw Error(where(cfg, values ? *values : el) + ": [[sweep.option]] needs values = [...] (strings, booleans or numbers)");
    for (const toml::node& v : *va) {
      std::string label;
      if (auto s = v.value_exact<std::string>()) label = *s;
      else if (auto b = v.value_exact<bool>()) label = *b ? "true" : "false";
      else if (auto i = v.value_exact<int64_t>()) label = std::to_string(*i);
      else if (auto d = v.value_exact<double>()) {
        std::ostringstream os;
        os << *d;
        label = os.str();
      } else
        throw Error(where(cfg, v) + ": option values must be strings, booleans or numbers");
      o.labels.push_back(label);
      o.where.push_back(where(cfg, v));
    }
    spec.n_combos *= o.labels.size();
    spec.options.push_back(std::move(o));
  }
}
}  // namespace


namespace {

// design, points, seed, range_of; returns the [sweep] points node (nullptr if absent).
const toml::node* parse_design(const config::Config& cfg, const toml::table& st, SweepSpec& spec) {
  spec.design_name = "grid";
  if (const toml::node* n = st.get("design")) {
    auto v = n->value<std::string>();
    if (!v || (*v != "grid" && *v != "lhs" && *v != "sobol" && *v != "one_at_a_time"))
      throw Error(where(cfg, *n) + ": design must be \"grid\", \"lhs\", \"sobol\" or \"one_at_a_time\"");
    spec.design_name = *v;
  }
  spec.design = spec.design_name == "grid"    ? Design::Grid
                : spec.design_name == "lhs"   ? Design::Lhs
                : spec.design_name == "sobol" ? Design::Sobol
                                              : Design::OneAtATime;
  if (const toml::node* n = st.get("seed")) {
    auto v = n->value_exact<int64_t>();
    if (!v || *v < 0) throw Error(where(cfg, *n) + ": 'seed' must be a non-negative integer");
    spec.seed = static_cast<std::uint64_t>(*v);
  }
  if (const toml::node* n = st.get("range_of")) {
    if (spec.design != Design::OneAtATime)
      throw Error(where(cfg, *n) + ": 'range_of' is for design = \"one_at_a_time\" (the range of each parameter alone)");
    spec.range_feature = config::text(cfg, *n, "range_of");
  }
  const toml::node* points = st.get("points");
  if (points) (void)positive_count(cfg, *points, "points");
  return points;
}

void parse_run_length(const config::Config& cfg, const toml::table& st, const toml::node& sn,
                      const config::SimulationSettings& sim, SweepSpec& spec) {
  spec.t_end_ms = sim.t_end_ms;
  spec.discard_ms = sim.discard_ms;
  if (const toml::node* n = st.get("t_end_ms")) {
    spec.t_end_ms = number(cfg, *n, "t_end_ms");
    if (!(spec.t_end_ms > 0)) throw Error(where(cfg, *n) + ": 't_end_ms' must be > 0");
  }
  if (const toml::node* n = st.get("discard_ms")) {
    spec.discard_ms = number(cfg, *n, "discard_ms");
    if (spec.discard_ms < 0) throw Error(where(cfg, *n) + ": 'discard_ms' must be >= 0");
  }
  if (spec.discard_ms >= spec.t_end_ms) {
    const toml::node* n = st.get("discard_ms") ? st.get("discard_ms") : st.get("t_end_ms");
    throw Error((n ? where(cfg, *n) : where(cfg, sn)) + ": discard_ms (" + std::to_string(spec.discard_ms) +
                ") must be less than t_end_ms (" + std::to_string(spec.t_end_ms) + ")");
  }
  config::check_run_times(spec.t_end_ms, std::min(sim.output_dt_ms, spec.t_end_ms), spec.discard_ms, where(cfg, sn) + ": [sweep]");
}

// Looks up a swept parameter by name (an error naming the line if unknown or swept twice).
struct ParameterLookup {
  const config::Config& cfg;
  const model::ParameterSet& params;
  std::set<std::string> seen;
  const model::Parameter& operator()(const toml::node& name_node, const std::string& name) {
    if (!params.contains(name)) {
      try {
        params.index(name);
      } catch (const Error& e) {
        throw Error(where(cfg, name_node) + ": " + e.what());
      }
    }
    if (!seen.insert(name).second) throw Error(where(cfg, name_node) + ": parameter '" + name + "' swept twice");
    return params.at(name);
  }
};

bool has_axes(Design d) { return d == Design::Grid || d == Design::OneAtATime; }

// names = [...], values = [[...], ...]: one grid axis whose rows set several parameters together.
void parse_linked(const config::Config& cfg, const toml::table& t, const toml::node& el, ParameterLookup& lookup,
                  std::size_t axis, SweepSpec& spec) {
  const toml::node* names = t.get("names");
  if (spec.design != Design::Grid) throw Error(where(cfg, *names) + ": linked 'names' are for design = \"grid\"");
  if (t.get("name") || t.get("lower") || t.get("upper") || t.get("points") || t.get("scale"))
    throw Error(where(cfg, *names) + ": 'names' takes only 'values' (one row of values per grid step)");
  const toml::array* na = names->as_array();
  if (!na || na->empty()) throw Error(where(cfg, *names) + ": 'names' must be a non-empty array of parameter names");
  const std::size_t first = spec.parameters.size();
  for (const toml::node& n : *na) {
    if (!n.is_string()) throw Error(where(cfg, n) + ": 'names' must hold parameter names (strings)");
    SweptParameter sp;
    sp.name = *n.value<std::string>();
    sp.unit = lookup(n, sp.name).unit;
    sp.axis = axis;
    spec.parameters.push_back(std::move(sp));
  }
  const toml::node* values = t.get("values");
  const toml::array* rows = values ? values->as_array() : nullptr;
  if (!rows || rows->empty())
    throw Error(where(cfg, values ? *values : el) + ": 'names' needs values = [[...], ...], one row per grid step");
  for (const toml::node& row : *rows) {
    const toml::array* ra = row.as_array();
    if (!ra || ra->size() != na->size())
      throw Error(where(cfg, row) + ": each row of 'values' needs " + std::to_string(na->size()) + " numbers");
    for (std::size_t c = 0; c < ra->size(); ++c) {
      SweptParameter& sp = spec.parameters[first + c];
      double x = number(cfg, *ra->get(c), sp.name);
      check_admissible(cfg, *ra->get(c), lookup.params.at(sp.name), x);
      sp.values.push_back(x);
    }
  }
}

// values = [...]: an explicit axis.
void parse_values(const config::Config& cfg, const toml::table& t, const model::Parameter& mp, SweepSpec& spec,
                  SweptParameter& sp) {
  const toml::node* values = t.get("values");
  if (!has_axes(spec.design))
    throw Error(where(cfg, *values) + ": 'values' is for design = \"grid\"; " + spec.design_name +
                " needs lower and upper");
  if (t.get("lower") || t.get("upper") || t.get("points") || t.get("scale"))
    throw Error(where(cfg, *values) + ": give either 'values' or 'lower'/'upper', not both");
  const toml::array* va = values->as_array();
  if (!va || va->empty()) throw Error(where(cfg, *values) + ": 'values' must be a non-empty array of numbers");
  for (const toml::node& v : *va) {
    double x = number(cfg, v, sp.name);
    check_admissible(cfg, v, mp, x);
    sp.values.push_back(x);
  }
}

// lower, upper [, points, scale]: a range, sampled by the design (or an axis of `points` values).
void parse_range(const config::Config& cfg, const toml::table& t, const toml::node& el, const model::Parameter& mp,
                 const toml::node* points_node, SweepSpec& spec, SweptParameter& sp) {
  const toml::node* lower = t.get("lower");
  const toml::node* upper = t.get("upper");
  const toml::node* pts = t.get("points");
  if (!lower || !upper)
    throw Error(where(cfg, el) + ": parameter '" + sp.name + "' needs 'values' or both 'lower' and 'upper'");
  sp.lower = number(cfg, *lower, "lower");
  sp.upper = number(cfg, *upper, "upper");
  check_admissible(cfg, *lower, mp, sp.lower);
  check_admissible(cfg, *upper, mp, sp.upper);
  if (!(sp.lower < sp.upper)) throw Error(where(cfg, *upper) + ": 'upper' must be greater than 'lower'");
  if (sp.log_scale && !(sp.lower > 0)) throw Error(where(cfg, *lower) + ": scale = \"log\" needs lower > 0");
  if (!has_axes(spec.design)) {
    if (pts) throw Error(where(cfg, *pts) + ": per-parameter 'points' is for design = \"grid\"; give [sweep] points");
    return;
  }
  std::size_t n = pts ? positive_count(cfg, *pts, "points") : points_node ? positive_count(cfg, *points_node, "points") : 0;
  if (n == 0)
    throw Error(where(cfg, el) + ": grid parameter '" + sp.name + "' needs 'points' (here or in [sweep]) or explicit 'values'");
  if (n == 1) throw Error(where(cfg, pts ? *pts : *points_node) + ": a lower/upper grid needs points >= 2");
  for (std::size_t k = 0; k < n; ++k) {
    double u = static_cast<double>(k) / static_cast<double>(n - 1);
    sp.values.push_back(k == n - 1 ? sp.upper : map_unit(sp, u));
  }
}

void parse_single(const config::Config& cfg, const toml::table& t, const toml::node& el, ParameterLookup& lookup,
                  const toml::node* points_node, std::size_t axis, SweepSpec& spec) {
  SweptParameter sp;
  sp.axis = axis;
  const toml::node* name = t.get("name");
  if (!name || !name->is_string())
    throw Error(where(cfg, el) + ": [[sweep.parameter]] needs name = \"...\" (or names = [...] with rows of values)");
  sp.name = *name->value<std::string>();
  const model::Parameter& mp = lookup(*name, sp.name);
  sp.unit = mp.unit;
  sp.base = mp.value;
  if (const toml::node* n = t.get("scale")) {
    auto v = n->value<std::string>();
    if (!v || (*v != "lin" && *v != "log")) throw Error(where(cfg, *n) + ": scale must be \"lin\" or \"log\"");
    sp.log_scale = *v == "log";
  }
  if (t.get("values")) parse_values(cfg, t, mp, spec, sp);
  else parse_range(cfg, t, el, mp, points_node, spec, sp);
  spec.parameters.push_back(std::move(sp));
}

// Full factorial, last axis varying fastest (C order, numpy.meshgrid indexing="ij"). Axes: one
// per [[sweep.parameter]] table (a `names` table is one axis of linked columns).
void grid_points(const config::Config& cfg, const toml::node& sn, std::size_t n_axes, SweepSpec& spec) {
  const std::size_t dim = spec.parameters.size();
  std::vector<std::size_t> axis_size(n_axes, 0);
  for (auto& p : spec.parameters) axis_size[p.axis] = p.values.size();
  std::size_t n = 1;
  for (std::size_t a : axis_size) {
    n *= a;
    if (n > kMaxPoints) throw Error(where(cfg, sn) + ": grid has more than " + std::to_string(kMaxPoints) + " points");
  }
  spec.n_design = n;
  spec.points.resize(n * dim);
  std::vector<std::size_t> row(n_axes);
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t rest = i;
    for (std::size_t a = n_axes; a-- > 0;) {
      row[a] = rest % axis_size[a];
      rest /= axis_size[a];
    }
    for (std::size_t d = 0; d < dim; ++d) spec.points[i * dim + d] = spec.parameters[d].values[row[spec.parameters[d].axis]];
  }
}

// Each parameter over its own axis with the others at their base values, parameter by
// parameter in the order given.
void one_at_a_time_points(SweepSpec& spec) {
  const std::size_t dim = spec.parameters.size();
  for (std::size_t d = 0; d < dim; ++d)
    for (double v : spec.parameters[d].values) {
      for (std::size_t k = 0; k < dim; ++k) spec.points.push_back(k == d ? v : spec.parameters[k].base);
      ++spec.n_design;
    }
}

void sampled_points(const config::Config& cfg, const toml::node& sn, const toml::node* pn, const toml::node* points_node,
                    SweepSpec& spec) {
  const std::size_t dim = spec.parameters.size();
  if (!points_node) throw Error(where(cfg, sn) + ": design = \"" + spec.design_name + "\" needs points = N in [sweep]");
  const std::size_t points = positive_count(cfg, *points_node, "points");
  if (spec.design == Design::Sobol && dim > kSobolMaxDim)
    throw Error(where(cfg, *pn) + ": sobol design supports at most " + std::to_string(kSobolMaxDim) + " parameters");
  std::vector<double> u = spec.design == Design::Lhs ? lhs_points(points, dim, spec.seed) : sobol_points(points, dim);
  spec.n_design = points;
  spec.points.resize(points * dim);
  for (std::size_t i = 0; i < points; ++i)
    for (std::size_t d = 0; d < dim; ++d) spec.points[i * dim + d] = map_unit(spec.parameters[d], u[i * dim + d]);
}

// Outer product with the option combinations: options slowest, the design repeats per combination.
void repeat_per_combination(const config::Config& cfg, const toml::node& sn, SweepSpec& spec) {
  if (spec.n_combos > 1) {
    if (spec.n_combos * spec.n_design > kMaxPoints) throw Error(where(cfg, sn) + ": too many points");
    std::vector<double> design = std::move(spec.points);
    spec.points.clear();
    for (std::size_t c = 0; c < spec.n_combos; ++c) spec.points.insert(spec.points.end(), design.begin(), design.end());
  }
  spec.n_points = spec.n_combos * spec.n_design;
}

}  // namespace

namespace {
// [sweep] with its [[sweep.parameter]] tables; with `explicit_points` (the caller's design) only
// ranges and run length are read and the design keys are refused.
SweepSpec parse_sweep_section(const config::Config& cfg, const model::ParameterSet& params,
                              const config::SimulationSettings& sim, bool explicit_points) {
  const toml::node* sn = cfg.table.get("sweep");
  if (!sn) throw Error(cfg.path + ": missing [sweep] section (docs/sweep.md)");
  const toml::table* st = sn->as_table();
  if (!st) throw Error(where(cfg, *sn) + ": 'sweep' must be a table ([sweep])");
  if (explicit_points)
    check_keys(cfg, *st, "sweep (its points come from [gsa])", {"t_end_ms", "discard_ms", "parameter"});
  else
    check_keys(cfg, *st, "sweep", {"design", "points", "seed", "t_end_ms", "discard_ms", "parameter", "option", "range_of"});
  SweepSpec spec;
  const toml::node* points_node = nullptr;
  if (explicit_points) spec.design = Design::Explicit, spec.design_name = "explicit";
  else points_node = parse_design(cfg, *st, spec);
  parse_run_length(cfg, *st, *sn, sim, spec);

  const toml::node* pn = st->get("parameter");
  const toml::array* arr = pn ? pn->as_array() : nullptr;
  if (!pn) throw Error(where(cfg, *sn) + ": [sweep] needs at least one [[sweep.parameter]] table");
  if (!arr || arr->empty() || !arr->is_array_of_tables())
    throw Error(where(cfg, *pn) + ": 'sweep.parameter' must be an array of tables ([[sweep.parameter]])");
  ParameterLookup lookup{cfg, params, {}};
  std::size_t n_axes = 0;
  for (const toml::node& el : *arr) {
    const toml::table& t = *el.as_table();
    check_keys(cfg, t, "[sweep.parameter]", {"name", "names", "values", "lower", "upper", "points", "scale"});
    if (t.get("names")) parse_linked(cfg, t, el, lookup, n_axes, spec);
    else parse_single(cfg, t, el, lookup, points_node, n_axes, spec);
    ++n_axes;
  }
  if (spec.design == Design::Explicit) return spec;  // the caller sets the points (set_unit_points)
  if (spec.design == Design::Grid) grid_points(cfg, *sn, n_axes, spec);
  else if (spec.design == Design::OneAtATime) one_at_a_time_points(spec);
  else sampled_points(cfg, *sn, pn, points_node, spec);
  parse_options(cfg, *st, spec);
  if (!spec.range_feature.empty() && spec.n_combos > 1)
    throw Error(where(cfg, *st->get("range_of")) + ": 'range_of' needs a sweep without [[sweep.option]]");
  repeat_per_combination(cfg, *sn, spec);
  return spec;
}
}  // namespace

SweepSpec parse_sweep(const config::Config& cfg, const model::ParameterSet& params,
                      const config::SimulationSettings& sim) {
  return parse_sweep_section(cfg, params, sim, false);
}

SweepSpec parse_sweep_ranges(const config::Config& cfg, const model::ParameterSet& params,
                             const config::SimulationSettings& sim) {
  return parse_sweep_section(cfg, params, sim, true);
}



config::Config config_for(const config::Config& cfg, const SweepSpec& spec, std::size_t combo) {
  config::Config c = cfg;
  if (spec.options.empty()) return c;
  toml::table* mt = c.table["model"].as_table();
  if (!mt) throw Error(cfg.path + ": missing [model] section");
  const toml::array* arr = cfg.table["sweep"]["option"].as_array();
  for (std::size_t k = 0; k < spec.options.size(); ++k) {
    const toml::node* v = arr->get(k)->as_table()->get("values")->as_array()->get(spec.option_value(combo, k));
    v->visit([&](auto&& x) { mt->insert_or_assign(spec.options[k].name, x); });
  }
  return c;
}

}  // namespace phasmid::sweep
