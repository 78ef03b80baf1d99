// phasmid cruse CONFIG: runs the Cruse (1980) coordination model and writes its trajectory,
// parameters and gait features to HDF5 (docs/cruse1980.md).
#include <fmt/format.h>

#include <iostream>
#include <nlohmann/json.hpp>

#include "app/verb.hpp"
#include "cruse/cruse1980_features.hpp"
#include "cruse/cruse1980_model.hpp"
#include "cruse/cruse1980_output.hpp"

namespace {

struct Options {
  std::string config;
  std::string out;
  std::vector<std::string> sets;
  bool json = false;
};

int run(const Options& o) {
  using namespace phasmid::cruse;
  auto loaded = load_config(o.config);
  for (const auto& s : o.sets) apply_set(loaded.parameters, s);
  const auto traj = simulate(loaded.parameters);
  const auto feat = measure(traj, loaded.parameters);
  if (!o.out.empty()) write_run(o.out, loaded, traj, feat, phasmid::app::command_line());
  if (o.json) {
    std::cout << features_json(feat).dump(2) << "\n";
  } else {
    std::cout << fmt::format("locked {}  period {:.1f} ms  lag L3->L1 {:.1f} ms  lag R3->R1 {:.1f} ms\nin phase:",
                             feat.locked ? "yes" : "no", feat.period_ms, feat.lag_L3_L1_ms, feat.lag_R3_R1_ms);
    for (const auto& pair : feat.in_phase_pairs) std::cout << " " << pair;
    std::cout << "\nphase of onset after OL1 (fraction of period):";
    for (int leg = 0; leg < kLegCount; ++leg) std::cout << fmt::format(" {}={:.3f}", leg_names()[leg], feat.phase[leg]);
    std::cout << "\n";
  }
  return 0;
}

phasmid::app::RegisterVerb reg{{"cruse", "Cruse (1980) six-oscillator leg coordination model",
                                [](CLI::App& sub) {
                                  auto o = std::make_shared<Options>();
                                  sub.add_option("config", o->config, "TOML config (file or embedded name)")->required();
                                  sub.add_option("-o,--output", o->out, "HDF5 output file");
                                  sub.add_option("--set", o->sets, "NAME=VALUE parameter override");
                                  sub.add_flag("--json", o->json, "print features as JSON");
                                  return std::function<int()>([o] { return run(*o); });
                                }}};

}  // namespace
