// phasmid params CONFIG [--json] [--set ...]: every named parameter with value, unit, source.
#include <nlohmann/json.hpp>
#include <iomanip>
#include <iostream>
#include <map>

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
  // Command times set during the run by [[triggers]]: their value here is only "never".
  std::map<std::string, std::string> triggered;
  for (const auto& tr : m->triggers())
    for (size_t k : tr.targets) triggered[m->parameters().at(k).name] = tr.event;
  if (a.json) {
    nlohmann::json out = nlohmann::json::array();
    for (auto& p : m->parameters().all()) {
      nlohmann::json e = {{"name", p.name}, {"value", p.value}, {"unit", p.unit}, {"source", p.source},
                          {"description", p.description}};
      if (triggered.count(p.name)) e["triggered_by"] = triggered[p.name];
      out.push_back(e);
    }
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  for (auto& p : m->parameters().all()) {
    std::cout << std::left << std::setw(40) << p.name << std::right << std::setw(12);
    if (triggered.count(p.name)) std::cout << "triggered";
    else std::cout << p.value;
    std::cout << "  " << std::left << std::setw(10) << p.unit << "  " << p.source;
    if (triggered.count(p.name)) std::cout << "; set during the run by [[triggers]] event " << triggered[p.name];
    std::cout << "\n";
  }
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
