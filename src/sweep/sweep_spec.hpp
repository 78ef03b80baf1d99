#pragma once
// A sweep's design (docs/sweep.md): which named parameters vary, over which points, with which
// [model] option combinations, and how long each point runs. config/sweep_section.hpp reads
// it from a config's [sweep] section.
#include <cstdint>
#include <string>
#include <vector>


namespace phasmid::sweep {

// Grid: the full factorial of the parameters' axes; Lhs, Sobol: `points` samples of the
// parameters' ranges; OneAtATime: each parameter over its own axis with the others at their
// base values (local stability ranges, e.g. Cruse's Table 1); Explicit: points the caller
// supplies as unit-cube rows (set_unit_points), e.g. the design of a global sensitivity analysis.
enum class Design { Grid, Lhs, Sobol, OneAtATime, Explicit };

struct SweptParameter {
  std::string name;
  std::string unit;
  std::vector<double> values;  // grid: the axis' values (explicit, from lower/upper/points, or a column of rows)
  double lower = 0, upper = 0;
  bool log_scale = false;
  double base = 0;             // the scenario's value (one_at_a_time holds it while others vary)
  std::size_t axis = 0;        // grid: parameters of one `names = [...]` table share an axis (linked values)
};

// A categorical axis over a key of [model] (e.g. gait = "tetrapod" | "tripod"): each value
// builds its own model; combined with the design as an outer product (options vary slowest).
struct SweptOption {
  std::string name;
  std::vector<std::string> labels;  // values as text ("tetrapod", "true", "2")
  std::vector<std::string> where;   // file:line of each value
};

struct SweepSpec {
  Design design = Design::Grid;
  std::string design_name;  // "grid" | "lhs" | "sobol" | "one_at_a_time"
  std::string range_feature;  // one_at_a_time: a 0/1 feature whose range of 1s per parameter is reported
  std::uint64_t seed = 0;
  std::vector<SweptParameter> parameters;
  std::vector<SweptOption> options;
  std::size_t n_design = 0;    // points of the design over the parameters
  std::size_t n_combos = 1;    // combinations of option values
  std::size_t n_points = 0;    // n_combos * n_design
  std::vector<double> points;  // n_points x parameters.size(), row-major, in parameter units
  double t_end_ms = 0, discard_ms = 0;

  std::vector<std::string> names() const;
  std::vector<std::string> units() const;
  double at(std::size_t point, std::size_t param) const { return points[point * parameters.size() + param]; }
  std::size_t combo_of(std::size_t point) const { return point / n_design; }
  // Index of option k's value in combination c (first option slowest).
  std::size_t option_value(std::size_t combo, std::size_t k) const;
  std::string describe_combo(std::size_t combo) const;  // e.g. "gait = tripod"
};

// Unit interval -> parameter value: linear in [lower, upper], or in log with log_scale;
// clamped so that rounding never leaves [lower, upper]. Shared with gsa/sampling.
double map_unit(const SweptParameter& p, double u);

// Design::Explicit: the sweep's points are `unit` (rows x parameters, row-major, in [0,1]),
// mapped to each parameter's range by map_unit. Replaces any points the spec had.
void set_unit_points(SweepSpec& spec, const std::vector<double>& unit);

}  // namespace phasmid::sweep
