#pragma once
// Model kinds (compare the verb registry in app/verb.hpp): each kind has a name — the value of
// `[model] type` in a config —, the [model] keys it accepts, and a factory that makes a
// Scenario from them. Adding a kind is its own files plus one line in registry.cpp
// (builtin_kinds); a kind may also register itself with RegisterModelKind from a file that is
// linked into the program directly (tests register a toy kind that way). docs/architecture.md.
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "config/toml_util.hpp"
#include "scenario/scenario.hpp"

namespace phasmid::scenario {

// The [model] table of a config, for a kind's factory: typed reads whose errors name file:line
// and the key. Keys outside the kind's declared ones were already refused.
class ModelSection {
 public:
  ModelSection(const config::Config& cfg, const toml::table& table) : cfg_(cfg), table_(table) {}
  const config::Config& config() const { return cfg_; }
  const toml::node* node(const std::string& key) const { return table_.get(key); }
  bool has(const std::string& key) const { return node(key) != nullptr; }
  std::string text(const std::string& key, const std::string& fallback) const;
  double number(const std::string& key, double fallback) const;
  bool boolean(const std::string& key, bool fallback) const;
  // "file:line" of the key (of the table where the key is absent), to prefix an error.
  std::string where(const std::string& key) const;
  // The value of `key` must be one of `allowed`; else an error listing them.
  std::string choice(const std::string& key, const std::string& fallback, const std::vector<std::string>& allowed) const;

 private:
  const config::Config& cfg_;
  const toml::table& table_;
};

struct ModelKind {
  std::string name;         // `[model] type = "<name>"`
  std::string description;  // one line, for `phasmid models`
  std::set<std::string> keys;  // [model] keys besides `type` and `description`
  std::function<std::unique_ptr<Scenario>(const ModelSection&)> make;
};

// Every registered kind, built-in first, in registration order.
const std::vector<ModelKind>& model_kinds();
// The kind called `name`; throws Error listing the kinds (and the nearest name) otherwise.
const ModelKind& model_kind(const std::string& name);

struct RegisterModelKind {
  explicit RegisterModelKind(ModelKind kind);
};

}  // namespace phasmid::scenario
