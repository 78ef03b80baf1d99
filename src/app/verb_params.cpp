// phasmid params CONFIG [--set ...] [--json]: every named parameter with value, unit, source.
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "app/options.hpp"
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
  auto scenario = config::build_scenario(cfg, a.sets);
  // Values set during the run (e.g. by [[triggers]]): their value here means nothing.
  std::map<std::string, std::string> set_by;
  for (const auto& [name, by] : scenario->run_time_parameters()) set_by[name] = by;
  if (a.json) {
    nlohmann::json out = nlohmann::json::array();
    for (auto& p : scenario->parameters().all()) {
      nlohmann::json e = {{"name", p.name}, {"value", p.value}, {"unit", p.unit}, {"source", p.source},
                          {"description", p.description}};
      if (set_by.count(p.name)) e["set_during_run_by"] = set_by[p.name];
      out.push_back(e);
    }
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  for (auto& p : scenario->parameters().all()) {
    std::cout << std::left << std::setw(40) << p.name << std::right << std::setw(12);
    if (set_by.count(p.name)) std::cout << "at run time";
    else std::cout << p.value;
    std::cout << "  " << std::left << std::setw(10) << p.unit << "  " << p.source;
    if (set_by.count(p.name)) std::cout << "; set during the run by " << set_by[p.name];
    std::cout << "\n";
  }
  return 0;
}

const RegisterVerb reg{{"params", "List every named parameter of a scenario: value, unit, source",
                        [](CLI::App& sub) {
                          auto a = std::make_shared<ParamsArgs>();
                          add_config_arg(sub, a->config);
                          add_sets(sub, a->sets);
                          add_json(sub, a->json);
                          return std::function<int()>([a] { return run_params(*a); });
                        }}};
}  // namespace
}  // namespace phasmid::app
