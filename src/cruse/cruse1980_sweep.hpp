#pragma once
// Stability sweep of Cruse (1980) Table 1: a parameter value counts as stable when, at every
// tested walking speed, all ten starting positions of Table 2 settle into one and the same
// locked pattern with L1-R2 and L2-R3 protracting together.
#include <string>
#include <vector>

#include "cruse/cruse1980_parameters.hpp"

namespace phasmid::cruse {

struct SweepAxis {
  std::string parameter;       // "T1", "T2" or "T0.<leg>"
  std::vector<double> values;  // grid
  std::vector<int> stable;     // 1/0 per value
  // Smallest and largest stable grid value (NaN if none), and whether the stable values form
  // one contiguous run of the grid.
  double stable_min = 0, stable_max = 0;
  bool contiguous = false;
};

// Evaluates one parameter setting over all starting positions and nominal periods.
bool is_stable(const Parameters& base, const std::vector<double>& periods_ms);

// The retraction rate giving nominal period `period_ms` with the parameters' gait.
double retraction_rate_for_period(const Parameters& p, double period_ms);
// `base` walking at nominal period `period_ms` for `cycles` periods (sweep, fit and tests).
Parameters at_period(const Parameters& base, double period_ms, double cycles = 60);

SweepAxis sweep_axis(const Parameters& base, const std::string& parameter, const std::vector<double>& values,
                     const std::vector<double>& periods_ms);

// The Table 1 axes: T0 of OL2..OR3, T1, T2 on the default grids (docs/cruse1980.md).
std::vector<SweepAxis> sweep_table1(const Parameters& base, const std::vector<double>& periods_ms);

}  // namespace phasmid::cruse
