#pragma once
// The [sweep] section of a scenario config (docs/sweep.md): which named parameters to vary,
// over which design, and how long to simulate each point.
#include <cstdint>
#include <string>
#include <vector>

#include "config/config.hpp"

namespace phasmid::sweep {

enum class Design { Grid, Lhs, Sobol };

struct SweptParameter {
  std::string name;
  std::string unit;
  std::vector<double> values;  // grid: explicit values (possibly generated from lower/upper/points)
  double lower = 0, upper = 0;
  bool log_scale = false;
};

struct SweepSpec {
  Design design = Design::Grid;
  std::string design_name;  // "grid" | "lhs" | "sobol"
  std::uint64_t seed = 0;
  std::vector<SweptParameter> parameters;
  std::size_t n_points = 0;
  std::vector<double> points;  // n_points x parameters.size(), row-major, in parameter units
  double t_end_ms = 0, discard_ms = 0;

  std::vector<std::string> names() const;
  std::vector<std::string> units() const;
  double at(std::size_t point, std::size_t param) const { return points[point * parameters.size() + param]; }
};

// Parses and validates [sweep] against the model's parameters (names, admissible ranges);
// every error names file:line. t_end_ms / discard_ms default to [simulation]'s.
SweepSpec parse_sweep(const config::Config& cfg, const model::ParameterSet& params,
                      const config::SimulationSettings& sim);

}  // namespace phasmid::sweep
