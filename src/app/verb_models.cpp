// phasmid models [CONFIG] [--json]: the registered model kinds with their [model] keys; with a
// config, the features its scenario reports (the feature catalogue).
#include <fmt/format.h>

#include <iostream>
#include <nlohmann/json.hpp>

#include "app/options.hpp"
#include "app/verb.hpp"
#include "config/config.hpp"
#include "scenario/registry.hpp"

namespace phasmid::app {
namespace {
struct ModelsArgs {
  std::string config;
  std::vector<std::string> sets;
  bool json = false;
};

// The models first, then under their own heading the analytic test problems.
void list_kinds(bool json) {
  using scenario::KindCategory;
  if (json) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& k : scenario::model_kinds())
      out.push_back({{"type", k.name}, {"description", k.description}, {"keys", k.keys},
                     {"category", scenario::category_name(k.category)}});
    std::cout << out.dump(2) << "\n";
    return;
  }
  for (const KindCategory c : {KindCategory::Model, KindCategory::TestProblem}) {
    std::cout << (c == KindCategory::Model ? "Models:\n"
                                            : "\nAnalytic test problems (known answers, for testing the methods):\n");
    for (const auto& k : scenario::model_kinds()) {
      if (k.category != c) continue;
      std::string keys;
      for (const auto& key : k.keys) keys += (keys.empty() ? "" : ", ") + key;
      std::cout << fmt::format("{:<18} {}\n{:<18} [model] keys: {}\n", k.name, k.description, "", keys.empty() ? "none" : keys);
    }
  }
}

void list_features(const ModelsArgs& a) {
  auto s = config::build_scenario(config::load_config(a.config), a.sets);
  nlohmann::json out = nlohmann::json::array();
  for (const auto& f : s->feature_catalogue()) {
    if (a.json)
      out.push_back({{"name", f.name}, {"unit", f.unit}, {"differentiable", f.differentiable}, {"description", f.description}});
    else std::cout << fmt::format("{:<44} {:<4} {}  {}\n", f.name, f.unit, f.differentiable ? "d" : "-", f.description);
  }
  if (a.json) std::cout << out.dump(2) << "\n";
}

const RegisterVerb reg{{"models", "List the model kinds ([model] type) or, for a config, the features its scenario reports",
                        [](CLI::App& sub) {
                          auto a = std::make_shared<ModelsArgs>();
                          sub.add_option("config", a->config, "scenario config (TOML): list its feature catalogue");
                          add_sets(sub, a->sets);
                          add_json(sub, a->json);
                          return std::function<int()>([a] {
                            if (a->config.empty()) list_kinds(a->json);
                            else list_features(*a);
                            return 0;
                          });
                        }}};
}  // namespace
}  // namespace phasmid::app
