#include "config/gsa_section.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "common/error.hpp"
#include "gsa/resolution.hpp"
#include "sweep/design.hpp"

namespace phasmid::config {
namespace {

constexpr std::int64_t kMaxCount = 10'000'000;  // also the sweep's cap on points (docs/sweep.md)
// Campolongo's selection keeps pool x pool distances and compares every pair of pool
// trajectories: 1000 is ~8 MB and a few seconds at 16 parameters.
constexpr std::int64_t kMaxPool = 1000;
// The Sobol' points dropped by skip are generated first (2D of them per point).
constexpr std::int64_t kMaxSkip = 65536;
// Resamples of the bootstrap: each one re-estimates every index (docs/gsa.md uses 1000).
constexpr std::int64_t kMaxBootstrap = 100000;

std::size_t count(const Config& cfg, const toml::node& n, const std::string& key, std::int64_t min,
                  std::int64_t max = kMaxCount) {
  auto v = n.value_exact<std::int64_t>();
  if (!v || *v < min || *v > max)
    throw Error(where(cfg, n) + ": [gsa] " + key + " must be an integer in [" + std::to_string(min) + ", " +
                std::to_string(max) + "]");
  return static_cast<std::size_t>(*v);
}

std::vector<std::string> feature_names(const Config& cfg, const toml::node& n,
                                       const std::vector<features::FeatureInfo>& catalogue) {
  const toml::array* a = n.as_array();
  if (!a || a->empty()) throw Error(where(cfg, n) + ": [gsa] features must be a non-empty list of feature names");
  std::vector<std::string> known, out;
  for (const auto& f : catalogue) known.push_back(f.name);
  std::set<std::string> seen;
  for (const toml::node& e : *a) {
    const std::string name = text(cfg, e, "features");
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      const std::string near = nearest(name, known);
      throw Error(where(cfg, e) + ": [gsa] unknown feature '" + name + "'" +
                  (near.empty() ? "" : " (did you mean '" + near + "'?)") + "; `phasmid features CONFIG` lists them");
    }
    if (!seen.insert(name).second) throw Error(where(cfg, e) + ": [gsa] feature '" + name + "' listed twice");
    out.push_back(name);
  }
  return out;
}

void parse_sobol_key(const Config& cfg, const std::string& key, const toml::node& n, gsa::SaltelliOptions& o) {
  if (key == "N") o.n_base = count(cfg, n, key, 2);
  else if (key == "second_order") o.second_order = boolean(cfg, n, key);
  else if (key == "scramble") o.scramble = boolean(cfg, n, key);
  else if (key == "skip") o.skip = count(cfg, n, key, 0, kMaxSkip);
}

void parse_morris_key(const Config& cfg, const std::string& key, const toml::node& n, gsa::MorrisOptions& o) {
  if (key == "trajectories") o.trajectories = count(cfg, n, key, 2);
  else if (key == "pool") o.pool = count(cfg, n, key, 0, kMaxPool);
  else if (key == "levels") {
    o.levels = static_cast<int>(count(cfg, n, key, 2));
    if (o.levels % 2) throw Error(where(cfg, n) + ": [gsa] levels must be even (Morris' grid with step p/(2(p-1)))");
  }
}

void check_pool(const Config& cfg, const toml::table& t, const gsa::MorrisOptions& o) {
  if (o.pool != 0 && o.pool <= o.trajectories)
    throw Error(where(cfg, *t.get("pool")) + ": [gsa] pool (" + std::to_string(o.pool) +
                ") must exceed trajectories (" + std::to_string(o.trajectories) + "), or be 0 for no selection");
}

// The node to blame for a design too large: the key if given, else the [gsa] table.
const toml::node& key_or_section(const Config& cfg, const char* key) {
  const toml::node* gn = cfg.table.get("gsa");
  const toml::node* n = gn->as_table()->get(key);
  return n ? *n : *gn;
}

}  // namespace

void check_gsa_design(const Config& cfg, const gsa::GsaSpec& spec, std::size_t n_parameters) {
  const bool sobol = spec.method == "sobol";
  const std::size_t max_dim = sweep::kSobolMaxDim / 2;
  if (sobol && n_parameters > max_dim) {
    const toml::array* pa = cfg.table["sweep"]["parameter"].as_array();
    const toml::node& at = pa && pa->size() > max_dim ? *pa->get(max_dim) : key_or_section(cfg, "method");
    throw Error(where(cfg, at) + ": [gsa] method = \"sobol\" varies at most " + std::to_string(max_dim) + " parameters (" +
                std::to_string(2 * max_dim) + " Sobol' dimensions), got " + std::to_string(n_parameters) +
                "; method = \"morris\" screens more");
  }
  const std::size_t per = sobol ? (spec.saltelli.second_order ? 2 * n_parameters + 2 : n_parameters + 2) : n_parameters + 1;
  const std::size_t n = sobol ? spec.saltelli.n_base : spec.morris.trajectories;
  const char* key = sobol ? "N" : "trajectories";
  if (n * per > static_cast<std::size_t>(kMaxCount))
    throw Error(where(cfg, key_or_section(cfg, key)) + ": [gsa] " + key + " = " + std::to_string(n) + " needs " +
                std::to_string(n * per) + " runs (" + std::to_string(per) + " each), more than the sweep's " +
                std::to_string(kMaxCount) + " points: at most " + key + " = " + std::to_string(kMaxCount / per));
}

gsa::GsaSpec parse_gsa_section(const Config& cfg, const std::vector<features::FeatureInfo>& catalogue) {
  const toml::node* gn = cfg.table.get("gsa");
  if (!gn) throw Error(cfg.path + ": missing [gsa] section (docs/gsa.md)");
  const toml::table* t = gn->as_table();
  if (!t) throw Error(where(cfg, *gn) + ": 'gsa' must be a table ([gsa])");
  gsa::GsaSpec spec;
  spec.bootstrap.seed = 1;
  if (const toml::node* m = t->get("method")) {
    spec.method = text(cfg, *m, "method");
    if (spec.method != "sobol" && spec.method != "morris")
      throw Error(where(cfg, *m) + ": [gsa] method must be \"sobol\" or \"morris\"");
  }
  const bool sobol = spec.method == "sobol";
  std::set<std::string> keys = {"method", "features", "seed", "bootstrap", "confidence", "resolution"};
  if (sobol) keys.insert({"N", "second_order", "scramble", "skip"});
  else keys.insert({"trajectories", "levels", "pool"});
  check_keys(cfg, *t, "gsa (method = \"" + spec.method + "\")", keys);
  const toml::node* fn = t->get("features");
  if (!fn) throw Error(where(cfg, *gn) + ": [gsa] needs features = [\"<feature>\", ...] (`phasmid features CONFIG`)");
  spec.features = feature_names(cfg, *fn, catalogue);
  for (auto&& [k, node] : *t) {
    const std::string key(k.str());
    if (key == "seed") {
      spec.saltelli.seed = spec.morris.seed = count(cfg, node, key, 0);
      spec.bootstrap.seed = spec.saltelli.seed + 1;  // its own stream, not the design's
    }
    else if (key == "bootstrap") spec.bootstrap.resamples = count(cfg, node, key, 0, kMaxBootstrap);
    else if (key == "confidence") {
      spec.bootstrap.confidence = number(cfg, node, key);
      if (!(spec.bootstrap.confidence > 0 && spec.bootstrap.confidence < 1))
        throw Error(where(cfg, node) + ": [gsa] confidence must lie in (0, 1), e.g. 0.95");
    } else if (key == "resolution") {
      spec.resolution = number(cfg, node, key);
      const std::string why = gsa::resolution_error(spec.resolution);
      if (!why.empty()) throw Error(where(cfg, node) + ": [gsa] " + why);
    } else if (sobol) parse_sobol_key(cfg, key, node, spec.saltelli);
    else parse_morris_key(cfg, key, node, spec.morris);
  }
  if (!sobol) check_pool(cfg, *t, spec.morris);
  return spec;
}

}  // namespace phasmid::config
