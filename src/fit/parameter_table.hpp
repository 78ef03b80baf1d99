#pragma once
// Parameters of a fit (PEtab's parameter table): which named parameters are estimated, on
// which scale (lin, log, log10), within which bounds, starting where. Bounds and nominal
// values are always given on the linear scale (as in PEtab); the optimiser works on the
// scaled values x = scale(theta) and Jacobians carry the chain rule d theta / d x.
#include <string>
#include <vector>

#include "fit/prior.hpp"
#include "fit/scale.hpp"

namespace phasmid::fit {

struct FitParameter {
  std::string id;          // phasmid parameter name, or a data time-offset parameter
  Scale scale = Scale::Lin;
  double lower = 0.0;      // linear scale
  double upper = 0.0;
  double nominal = 0.0;    // start value (estimated) or fixed value (not estimated)
  bool estimate = true;
  std::string origin;      // "params.tsv:4" or "cfg.toml:12", for error messages
  Prior prior;             // objectivePriorType/objectivePriorParameters (samplers only)
};

// Reads a PEtab parameter table (tab-separated, header line naming the columns; required:
// parameterId, parameterScale, lowerBound, upperBound, nominalValue, estimate; optional:
// objectivePriorType, objectivePriorParameters (fit/prior.hpp); other columns are ignored).
// Errors are one line naming file:line.
std::vector<FitParameter> read_parameter_table(const std::string& path);
std::vector<FitParameter> parse_parameter_table(const std::string& text, const std::string& origin);

// Writes the same format (used for the synthetic data set and for `--parameters` round trips).
std::string format_parameter_table(const std::vector<FitParameter>& params);

// A parameterId names one model parameter, or with wildcards several that are tied to one
// fitted value: '*' matches any run of characters, '?' exactly one ("switch.S?.at_400ms"
// ties switch.SL.at_400ms and switch.SR.at_400ms).
bool is_parameter_pattern(const std::string& id);
bool parameter_id_matches(const std::string& id, const std::string& name);

// Checks one parameter for consistency (bounds ordered, nominal inside, log scales positive).
void validate(const FitParameter& p);

}  // namespace phasmid::fit
