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

#include "scenario/scenario.hpp"

namespace phasmid::scenario {

// The [model] table of a config, for a kind's factory: typed reads whose errors name file:line
// and the key. Keys outside the kind's declared ones were already refused. The config layer
// implements it over the parsed file (config/model_section.hpp), so that the kinds read their
// keys without knowing TOML or the config layer.
class ModelSection {
 public:
  virtual ~ModelSection() = default;
  virtual bool has(const std::string& key) const = 0;
  virtual std::string text(const std::string& key, const std::string& fallback) const = 0;
  virtual double number(const std::string& key, double fallback) const = 0;
  virtual bool boolean(const std::string& key, bool fallback) const = 0;
  // A list of numbers, each with the "file:line" of its element (to blame one in an error);
  // empty when the key is absent. A value that is not a non-empty list is an error
  // "file:line: <key> must be <what>".
  struct Located {
    double value = 0;
    std::string where;
  };
  virtual std::vector<Located> numbers(const std::string& key, const std::string& what) const = 0;
  // "file:line" of the key (of the table where the key is absent), to prefix an error.
  virtual std::string where(const std::string& key) const = 0;
  // The value of `key` must be one of `allowed`; else an error listing them.
  std::string choice(const std::string& key, const std::string& fallback, const std::vector<std::string>& allowed) const;
};

// A kind is a model (of walking, or of its parts) or an analytic test problem: a function or
// oscillator with a known answer that exists to test the methods (GSA indices, continuation,
// the solver's event handling). `phasmid models` lists the two apart.
enum class KindCategory { Model, TestProblem };

struct ModelKind {
  std::string name;         // `[model] type = "<name>"`
  std::string description;  // one line, for `phasmid models`
  std::set<std::string> keys;  // [model] keys besides `type` and `description`
  std::function<std::unique_ptr<Scenario>(const ModelSection&)> make;
  KindCategory category = KindCategory::Model;  // set by the registration (builtin_kinds.def)
};

// "model" | "test_problem" (`phasmid models --json`).
std::string category_name(KindCategory c);

// Every registered kind, built-in first, in registration order.
const std::vector<ModelKind>& model_kinds();
// The kind called `name`; throws Error listing the kinds (and the nearest name) otherwise.
const ModelKind& model_kind(const std::string& name);

struct RegisterModelKind {
  explicit RegisterModelKind(ModelKind kind);
};

}  // namespace phasmid::scenario
