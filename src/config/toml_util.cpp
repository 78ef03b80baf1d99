#include "config/toml_util.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/embedded.hpp"
#include "common/error.hpp"
#include "io/text_file.hpp"

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

double number(const Config& cfg, const toml::node& node, const std::string& key) {
  auto v = node.value<double>();
  // toml++ converts only integers a double holds exactly; a larger one is still a number (to be
  // refused by its bound, not as "not a number").
  if (!v && node.is_integer()) v = static_cast<double>(*node.value<std::int64_t>());
  if (!v) throw Error(where(cfg, node) + ": '" + key + "' must be a number");
  if (!std::isfinite(*v)) throw Error(where(cfg, node) + ": '" + key + "' must be a finite number");
  return *v;
}

namespace {
std::string g(double v) {
  std::ostringstream os;
  os.precision(10);  // enough to tell a value just beyond a bound from the bound
  os << v;
  return os.str();
}
}  // namespace

double number_in(const Config& cfg, const toml::node& node, const std::string& key, double lo, double hi) {
  const double v = number(cfg, node, key);
  if (v < lo || v > hi)
    throw Error(where(cfg, node) + ": '" + key + "' = " + g(v) + " is outside [" + g(lo) + ", " + g(hi) + "]");
  return v;
}

void check_run_times(double t_end_ms, double output_dt_ms, double discard_ms, const std::string& where) {
  if (!(t_end_ms > 0 && t_end_ms <= kMaxTEndMs))
    throw Error(where + ": t_end_ms = " + g(t_end_ms) + " must be in (0, " + g(kMaxTEndMs) + "] ms");
  if (!(discard_ms >= 0 && discard_ms < t_end_ms))
    throw Error(where + ": discard_ms = " + g(discard_ms) + " must be in [0, t_end_ms = " + g(t_end_ms) + ")");
  if (!(output_dt_ms >= kMinOutputDtMs && output_dt_ms <= t_end_ms))
    throw Error(where + ": output_dt_ms = " + g(output_dt_ms) + " must be in [" + g(kMinOutputDtMs) +
                ", t_end_ms] ms");
  if ((t_end_ms - discard_ms) / output_dt_ms > kMaxOutputSamples)
    throw Error(where + ": (t_end_ms - discard_ms) / output_dt_ms = " + g((t_end_ms - discard_ms) / output_dt_ms) +
                " samples; at most " + g(kMaxOutputSamples) + " (raise output_dt_ms)");
}

const std::vector<std::string>& known_sections() {
  static const std::vector<std::string> sections = {
      "model", "parameters", "simulation", "triggers", "sensitivity", "fit", "sweep",
      "gsa",           // [gsa] of `phasmid gsa`
      "continuation",  // [continuation] of `phasmid continue`
      "sample",        // [sample] of `phasmid sample`
  };
  return sections;
}

bool boolean(const Config& cfg, const toml::node& node, const std::string& key) {
  if (auto v = node.value<bool>()) return *v;
  if (auto v = node.value<int64_t>(); v && (*v == 0 || *v == 1)) return *v == 1;
  throw Error(where(cfg, node) + ": '" + key + "' must be true or false");
}

void check_keys(const Config& cfg, const toml::table& t, const std::string& section,
                const std::set<std::string>& allowed) {
  for (auto& [k, v] : t) {
    const std::string key(k.str());
    if (allowed.count(key)) continue;
    std::string list;
    for (auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    const std::string near = nearest(key, {allowed.begin(), allowed.end()});
    throw Error(where(cfg, v) + ": unknown key '" + key + "' in [" + section + "]" +
                (near.empty() ? "" : " (did you mean '" + near + "'?)") + " (allowed: " + list + ")");
  }
}

namespace {
void flatten_into(const toml::table& t, const std::string& prefix,
                  std::vector<std::pair<std::string, const toml::node*>>& out) {
  for (auto& [k, v] : t) {
    std::string name = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (auto sub = v.as_table()) flatten_into(*sub, name, out);
    else out.emplace_back(name, &v);
  }
}
}  // namespace

std::vector<std::pair<std::string, const toml::node*>> flatten(const toml::table& table) {
  std::vector<std::pair<std::string, const toml::node*>> out;
  flatten_into(table, "", out);
  return out;
}

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
  const auto& known = known_sections();
  for (auto& [k, v] : cfg.table) {
    const std::string key(k.str());
    if (key == "cruse1980" || std::find(known.begin(), known.end(), key) != known.end()) continue;  // [cruse1980]: build_scenario says what replaced it
    const std::string near = nearest(key, known);
    throw Error(where(cfg, v) + ": unknown section [" + key + "]" + (near.empty() ? "" : " (did you mean [" + near + "]?)") +
                "; the sections are described in docs/config.md");
  }
  return cfg;
}

Config load_config(const std::string& path) {
  if (fs::exists(path)) {
    return parse_config(io::read_text_file(path, "config"), path);
  }
  const auto& files = embedded::files();
  for (const std::string& key : {path, "configs/" + path, "configs/" + path + ".toml"}) {
    auto it = files.find(key);
    if (it != files.end()) return parse_config(it->second, "embedded:" + key);
  }
  throw Error(path + ": no such config file");
}

}  // namespace phasmid::config
