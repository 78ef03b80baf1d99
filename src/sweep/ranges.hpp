#pragma once
// The range analysis of a one-at-a-time sweep (docs/sweep.md, "Ranges"): for each parameter
// varied alone, the values at which a 0/1 feature (e.g. the Cruse model's `table1_stable`) is
// 1, the smallest and largest of them, and whether they form one contiguous run of the axis.
// This is how Cruse (1980) Table 1 reports stability ranges (docs/cruse1980.md).
#include <string>
#include <vector>

#include "io/h5_file.hpp"
#include "sweep/sweep_spec.hpp"

namespace phasmid::sweep {

struct ParameterRange {
  std::string parameter;
  std::vector<double> values;  // the parameter's axis
  std::vector<int> in_range;   // 1 where the feature is 1 (a failed point or NaN counts as 0)
  double lower = 0, upper = 0;  // smallest and largest value in range (NaN if none)
  bool contiguous = false;     // the values in range form one run of the axis
};

// `feature` holds the feature's value at every point of `spec` (design order).
std::vector<ParameterRange> one_at_a_time_ranges(const SweepSpec& spec, const std::vector<double>& feature);

// /sweep/ranges/<parameter>/{values, in_range, lower, upper, contiguous}, attribute `feature`.
void write_ranges_h5(io::H5Writer& w, const std::string& feature, const std::vector<ParameterRange>& ranges);
// The same, read back from a sweep file (empty if it has none).
std::vector<ParameterRange> read_ranges_h5(const io::H5Reader& r);

}  // namespace phasmid::sweep
