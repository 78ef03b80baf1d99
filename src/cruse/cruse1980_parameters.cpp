#include "cruse/cruse1980_parameters.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace phasmid::cruse {

const std::array<std::string, kLegCount>& leg_names() {
  static const std::array<std::string, kLegCount> names = {"L1", "L2", "L3", "R1", "R2", "R3"};
  return names;
}

namespace {
const char* kPaper = "Cruse (1980)";
const char* kChoice = "phasmid choice, docs/cruse1980.md";
}  // namespace

void Parameters::add(std::string name, double value, std::string unit, std::string source) {
  index_[name] = list_.size();
  list_.push_back({std::move(name), value, std::move(unit), std::move(source)});
}

Parameters::Parameters() {
  // Position unit: one tenth of the AEP-PEP interval of OL1 (Cruse 1980 Fig. 3, Fig. 5).
  add("start_position", 1, "1", std::string(kPaper) + " Table 2 row");
  add("raster_ms", 20, "ms", std::string(kPaper) + " Sect. 2 (Fortran time raster)");
  add("duration_ms", 30000, "ms", kChoice);
  add("output_step_ms", 20, "ms", kChoice);
  // 10/900 per ms gives a 1000 ms period with the 100 ms gait-II protraction.
  add("retraction_rate", 10.0 / 900.0, "unit/ms", kChoice);
  add("protraction_rate", 0.1, "unit/ms",
      std::string(kPaper) + " Sect. 2: protraction ~100 ms from T0(OL1)=10 in gait II");
  add("gait1.protraction_to_retraction_rate", 1.5, "1", kChoice);
  add("T0.L1", 10.0, "unit", std::string(kPaper) + " Table 1 / Sect. 3 (fixed at 10)");
  add("T0.L2", 10.2, "unit", std::string(kPaper) + " Table 1 T0 min");
  add("T0.L3", 10.2, "unit", std::string(kPaper) + " Table 1 T0 min");
  add("T0.R1", 10.2, "unit", std::string(kPaper) + " Table 1 T0 min");
  add("T0.R2", 10.3, "unit", std::string(kPaper) + " Table 1 T0 min");
  add("T0.R3", 10.3, "unit", std::string(kPaper) + " Table 1 T0 min");
  add("T1", 7.0, "unit", std::string(kPaper) + " Table 1 range 5-9 (midpoint)");
  add("T2", 5.5, "unit", std::string(kPaper) + " Table 1 range 1-10 (midpoint)");
  // Fig. 3 curves are not printed: piecewise-linear in the period through these nodes, chosen
  // so that the steady state has the inter-leg delay of docs/cruse1980.md (gait II).
  const double sl[] = {5.0, 6.0, 6.43, 6.67, 6.96, 7.11};
  const double s1[] = {1.67, 2.0, 2.14, 2.22, 2.32, 2.37};
  for (std::size_t i = 0; i < switch_node_periods().size(); ++i) {
    const std::string at = ".at_" + std::to_string(static_cast<int>(switch_node_periods()[i])) + "ms";
    add("switch.SL" + at, sl[i], "unit", kChoice);
    add("switch.SR" + at, sl[i], "unit", kChoice);
    add("switch.SL1R1" + at, s1[i], "unit", kChoice);
  }
  // Gait I: fixed switch points (Cruse 1980 Sect. 3 a); values give a tripod (docs).
  add("gait1.switch.SL", 5.0 / 3.0, "unit", kChoice);
  add("gait1.switch.SR", 5.0 / 3.0, "unit", kChoice);
  add("gait1.switch.SL1R1", 5.0 / 3.0, "unit", kChoice);
  add("coupling.contralateral", 1, "1",
      std::string(kPaper) + " Sect. 2: cross connections can be switched off centrally");
  add("analysis.cycles", 5, "1", kChoice);
  add("analysis.in_phase_tolerance_ms", 20, "ms", std::string(kChoice) + " (one raster step)");
}

bool Parameters::has(const std::string& name) const { return index_.count(name) > 0; }

double Parameters::get(const std::string& name) const {
  auto it = index_.find(name);
  if (it == index_.end()) throw Error(fmt::format("cruse1980: unknown parameter '{}'", name));
  return list_[it->second].value;
}

void Parameters::set(const std::string& name, double value) {
  auto it = index_.find(name);
  if (it == index_.end()) throw Error(fmt::format("cruse1980: unknown parameter '{}'", name));
  if (!std::isfinite(value)) throw Error(fmt::format("cruse1980: parameter '{}' is not finite", name));
  if (name == "start_position" && (value < 1 || value > 10 || value != std::floor(value)))
    throw Error(fmt::format("cruse1980: start_position must be an integer 1..10 (Table 2), got {}", value));
  if (name == "analysis.cycles" && (value < 1 || value != std::floor(value)))
    throw Error(fmt::format("cruse1980: analysis.cycles must be a positive integer, got {}", value));
  if ((name == "raster_ms" || name == "duration_ms" || name == "output_step_ms" || name == "retraction_rate" ||
       name == "protraction_rate" || name == "gait1.protraction_to_retraction_rate") &&
      value <= 0)
    throw Error(fmt::format("cruse1980: parameter '{}' must be positive, got {}", name, value));
  list_[it->second].value = value;
}

double Parameters::t0(int leg) const { return get("T0." + leg_names()[leg]); }
int Parameters::start_position() const { return static_cast<int>(get("start_position")); }

double Parameters::protraction_rate() const {
  // Gait I: protraction time proportional to the period, i.e. the return rate scales with the
  // retraction rate (docs/cruse1980.md discusses the paper's "inversely proportional" wording).
  if (gait == Gait::I) return get("gait1.protraction_to_retraction_rate") * get("retraction_rate");
  return get("protraction_rate");
}

double Parameters::nominal_period_ms() const {
  const double amplitude = t0(L1);
  return amplitude / get("retraction_rate") + amplitude / protraction_rate();
}

const std::vector<double>& switch_node_periods() {
  static const std::vector<double> periods = {400, 600, 800, 1000, 1500, 2000};
  return periods;
}

double Parameters::switch_position(const std::string& which) const {
  if (gait == Gait::I) return get("gait1.switch." + which);
  // Linear between nodes, constant beyond the first and last node.
  const auto& nodes = switch_node_periods();
  auto value = [&](std::size_t i) {
    return get("switch." + which + ".at_" + std::to_string(static_cast<int>(nodes[i])) + "ms");
  };
  const double period = nominal_period_ms();
  if (period <= nodes.front()) return value(0);
  for (std::size_t i = 1; i < nodes.size(); ++i)
    if (period <= nodes[i]) {
      const double w = (period - nodes[i - 1]) / (nodes[i] - nodes[i - 1]);
      return (1 - w) * value(i - 1) + w * value(i);
    }
  return value(nodes.size() - 1);
}

std::array<double, kLegCount> table2_start(int position) {
  // Rows of Table 2 as printed (OR3, OR2, OR1, OL3, OL2, OL1), one column per position no.
  static const double or3[10] = {1, 2, 4, 6, 8, 9, 9, 2, 7, 1};
  static const double or2[10] = {1, 2, 4, 6, 8, 9, 4, 5, 5, 10};
  static const double or1[10] = {1, 2, 4, 6, 8, 9, 2, 8, 3, 2};
  static const double ol3[10] = {1, 2, 4, 6, 8, 9, 8, 8, 7, 1};
  static const double ol2[10] = {1, 2, 4, 6, 8, 9, 5, 5, 5, 5};
  static const double ol1[10] = {1, 2, 4, 6, 8, 9, 1, 1, 3, 7};
  if (position < 1 || position > 10)
    throw Error(fmt::format("cruse1980: start_position must be 1..10 (Table 2), got {}", position));
  const int c = position - 1;
  return {ol1[c], ol2[c], ol3[c], or1[c], or2[c], or3[c]};
}

}  // namespace phasmid::cruse
