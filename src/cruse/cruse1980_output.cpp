#include "cruse/cruse1980_output.hpp"

#include "io/h5_file.hpp"

namespace phasmid::cruse {

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
