// phasmid cruse-sweep CONFIG: the Table 1 stability sweep of the Cruse (1980) model over
// T0 (OL2..OR3), T1 and T2 (docs/cruse1980.md, HDF5 group /sweep).
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/verb.hpp"
#include "common/error.hpp"
#include "cruse/cruse1980_sweep.hpp"
#include "io/h5_file.hpp"

namespace {

struct Options {
  std::string config;
  std::string out;
  std::vector<std::string> sets;
  std::vector<double> periods{400, 500, 700, 1000, 1500, 2000};
  bool json = false;
};

int run(const Options& o) {
  using namespace phasmid::cruse;
  auto loaded = load_config(o.config);
  for (const auto& s : o.sets) apply_set(loaded.parameters, s);
  for (double p : o.periods)
    if (!(p > 0)) throw phasmid::Error(fmt::format("--periods: period must be positive, got {}", p));
  const auto axes = sweep_table1(loaded.parameters, o.periods);
  if (!o.out.empty()) {
    phasmid::io::H5Writer w(o.out);
    w.write_run_info({loaded.text, phasmid::app::command_line()});
    w.set_attribute("/", "model", "cruse1980");
    w.write("/sweep/periods_ms", o.periods, "ms");
    for (const auto& a : axes) {
      const std::string g = "/sweep/" + a.parameter;
      w.write(g + "/values", a.values, "unit");
      std::vector<double> stable(a.stable.begin(), a.stable.end());
      w.write(g + "/stable", stable, "1");
      w.write_scalar(g + "/stable_min", a.stable_min, "unit");
      w.write_scalar(g + "/stable_max", a.stable_max, "unit");
      w.write_scalar(g + "/contiguous", a.contiguous ? 1.0 : 0.0, "1");
    }
    w.commit();
  }
  if (o.json) {
    nlohmann::json j = nlohmann::json::array();
    for (const auto& a : axes) {
      auto num = [](double v) { return std::isnan(v) ? nlohmann::json() : nlohmann::json(v); };
      j.push_back({{"parameter", a.parameter}, {"stable_min", num(a.stable_min)}, {"stable_max", num(a.stable_max)},
                   {"contiguous", a.contiguous}, {"values", a.values}, {"stable", a.stable}});
    }
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << "parameter  stable_min  stable_max  contiguous\n";
    for (const auto& a : axes)
      std::cout << fmt::format("{:<10} {:>10.2f} {:>11.2f}  {}\n", a.parameter, a.stable_min, a.stable_max,
                               a.contiguous ? "yes" : "no");
  }
  return 0;
}

phasmid::app::RegisterVerb reg{{"cruse-sweep", "Cruse (1980) Table 1 stability ranges of T0, T1, T2",
                                [](CLI::App& sub) {
                                  auto o = std::make_shared<Options>();
                                  sub.add_option("config", o->config, "TOML config (file or embedded name)")->required();
                                  sub.add_option("-o,--output", o->out, "HDF5 output file");
                                  sub.add_option("--set", o->sets, "NAME=VALUE parameter override");
                                  sub.add_option("--periods", o->periods, "nominal periods (ms) tested")->delimiter(',');
                                  sub.add_flag("--json", o->json, "print the ranges as JSON");
                                  return std::function<int()>([o] { return run(*o); });
                                }}};

}  // namespace
