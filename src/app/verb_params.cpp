// phasmid params CONFIG [--json] [--set ...]: every named parameter with value, unit, source.
#include <nlohmann/json.hpp>
#include <iomanip>
#include <iostream>

#include "app/verb.hpp"
#include "config/config.hpp"

namespace phasmid::app {
namespace {
struct ParamsArgs {
  std::string config;
  std::vector<std::string> sets;
  bool json = false;
};

int run_params(const ParamsArgs& a) {
  auto cfg = config::load_config(a.config);
  auto m = config::build_model(cfg, a.sets);
  if (a.json) {
    nlohmann::json out = nlohmann::json::array();
    for (auto& p : m->parameters().all())
      out.push_back({{"name", p.name}, {"value", p.value}, {"unit", p.unit}, {"source", p.source},
                     {"description", p.description}});
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  for (auto& p : m->parameters().all())
    std::cout << std::left << std::setw(40) << p.name << std::right << std::setw(12) << p.value << "  "
              << std::left << std::setw(10) << p.unit << "  " << p.source << "\n";
  return 0;
}

const RegisterVerb reg{{"params", "List every named parameter of a scenario: value, unit, source",
                        [](CLI::App& sub) {
                          auto a = std::make_shared<ParamsArgs>();
                          sub.add_option("config", a->config, "scenario config (TOML)")->required();
                          sub.add_option("--set", a->sets, "override a parameter: NAME=VALUE");
                          sub.add_flag("--json", a->json, "JSON output");
                          return std::function<int()>([a] { return run_params(*a); });
                        }}};
}  // namespace
}  // namespace phasmid::app
