#pragma once
// Named parameters of the Cruse (1980) leg-coordination model: every number the model uses,
// with unit and source. A cruse1980 scenario (cruse1980_scenario.cpp) exposes them by name.
#include <array>
#include <map>
#include <string>
#include <vector>

namespace phasmid::cruse {

// Leg order used everywhere in this module (and in the HDF5 output).
enum Leg { L1 = 0, L2, L3, R1, R2, R3 };
constexpr int kLegCount = 6;
const std::array<std::string, kLegCount>& leg_names();

enum class Gait { II, I };                   // Graham (1972): adult gait II, 1st-instar gait I
enum class Stepping { Raster, Continuous };  // Cruse's 20 ms Fortran raster, or event-exact

struct NamedParameter {
  std::string name;
  double value;
  std::string unit;
  std::string source;
};

class Parameters {
 public:
  Parameters();  // defaults: gait II (configs/cruse1980_gait2.toml repeats them)

  Gait gait = Gait::II;
  Stepping stepping = Stepping::Raster;

  double get(const std::string& name) const;  // throws phasmid::Error on unknown name
  void set(const std::string& name, double value);
  bool has(const std::string& name) const;
  const std::vector<NamedParameter>& all() const { return list_; }

  // Convenience accessors for the model.
  double t0(int leg) const;
  int start_position() const;
  // Nominal period from the retraction rate: time to retract 0 -> T0(OL1) plus protraction back.
  double nominal_period_ms() const;
  double protraction_rate() const;  // position units per ms, by gait
  // Switch position (Fig. 3) of switch "SL", "SR" or "SL1R1" at the nominal period (gait II),
  // or the fixed gait-I switch point.
  double switch_position(const std::string& which) const;

 private:
  std::vector<NamedParameter> list_;
  std::map<std::string, std::size_t> index_;
  void add(std::string name, double value, std::string unit, std::string source);
};

// Periods (ms) at which the Fig. 3 switch curves are given as parameters "switch.<S>.at_<P>ms".
const std::vector<double>& switch_node_periods();

// Table 2 of Cruse (1980): initial oscillator outputs, row `position` (1..10), legs L1..R3.
std::array<double, kLegCount> table2_start(int position);

}  // namespace phasmid::cruse
