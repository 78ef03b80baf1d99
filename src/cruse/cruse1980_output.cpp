#include "cruse/cruse1980_output.hpp"

#include "io/h5_file.hpp"

namespace phasmid::cruse {

nlohmann::json features_json(const Features& f) {
  nlohmann::json j;
  j["locked"] = f.locked;
  j["period_ms"] = f.period_ms;
  j["lag_L3_L1_ms"] = f.lag_L3_L1_ms;
  j["lag_R3_R1_ms"] = f.lag_R3_R1_ms;
  j["in_phase_pairs"] = f.in_phase_pairs;
  for (int leg = 0; leg < kLegCount; ++leg) j["phase"][leg_names()[leg]] = f.phase[leg];
  return j;
}

// The resolved config: the file text followed by every parameter value actually used.
std::string resolved_config(const LoadedConfig& config) {
  std::string text = config.text + "\n# resolved [cruse1980] values\n";
  text += std::string("# gait = \"") + (config.parameters.gait == Gait::I ? "I" : "II") + "\"\n";
  text += std::string("# time_stepping = \"") +
          (config.parameters.stepping == Stepping::Raster ? "raster" : "continuous") + "\"\n";
  for (const auto& p : config.parameters.all()) text += "# " + p.name + " = " + std::to_string(p.value) + "\n";
  return text;
}

void write_run(const std::string& path, const LoadedConfig& config, const Trajectory& run, const Features& f,
               const std::string& command) {
  io::H5Writer w(path);
  // The parameters actually used: --set overrides are part of the run, not of the file text.
  w.write_run_info({resolved_config(config), command});
  w.set_attribute("/", "model", "cruse1980");
  write_run_contents(w, config.parameters, run, f);
  w.commit();
}

void write_run_contents(io::H5Writer& w, const Parameters& p, const Trajectory& run, const Features& f) {
  w.write("/trajectory/time", run.time_ms, "ms");
  for (int leg = 0; leg < kLegCount; ++leg) {
    const auto& name = leg_names()[leg];
    w.write("/trajectory/position/" + name, run.position[leg], "unit (1/10 of OL1 AEP-PEP interval)");
    w.write("/trajectory/protraction/" + name, run.protraction[leg], "1");
    w.write("/events/protraction_onset/" + name, run.onsets_ms[leg], "ms");
  }
  std::vector<std::string> names, units;
  std::vector<double> values;
  for (const auto& q : p.all()) {
    names.push_back(q.name);
    values.push_back(q.value);
    units.push_back(q.unit);
  }
  w.write("/parameters/names", names);
  w.write("/parameters/values", values, "see /parameters/units");
  w.write("/parameters/units", units);
  w.write_scalar("/features/locked", f.locked ? 1.0 : 0.0, "1");
  w.write_scalar("/features/period_ms", f.period_ms, "ms");
  w.write_scalar("/features/lag_L3_L1_ms", f.lag_L3_L1_ms, "ms");
  w.write_scalar("/features/lag_R3_R1_ms", f.lag_R3_R1_ms, "ms");
  std::vector<double> phases(f.phase.begin(), f.phase.end());
  w.write("/features/phase", phases, "1 (fraction of period after OL1 onset; legs L1..R3)");
  w.write("/features/in_phase_pairs", f.in_phase_pairs);
}

}  // namespace phasmid::cruse
