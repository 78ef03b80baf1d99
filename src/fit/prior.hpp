#pragma once
// Priors of estimated parameters as PEtab's parameter table declares them (columns
// objectivePriorType and objectivePriorParameters, "a;b"; docs/sampling.md). Types on the
// linear value theta: uniform (lower; upper), normal (mean; sd), laplace (location; scale),
// logNormal and logLaplace (of ln theta); on the parameter's scale x = scale(theta):
// parameterScaleUniform, parameterScaleNormal, parameterScaleLaplace. Without a declared prior
// a parameter is uniform on its scale within its bounds (PEtab's default), and every prior is
// truncated to the bounds.
#include <string>

#include "fit/scale.hpp"

namespace phasmid::fit {

enum class PriorType {
  ParameterScaleUniform,
  ParameterScaleNormal,
  ParameterScaleLaplace,
  Uniform,
  Normal,
  Laplace,
  LogNormal,
  LogLaplace,
};

struct Prior {
  bool declared = false;  // false: uniform on the parameter's scale within its bounds
  PriorType type = PriorType::ParameterScaleUniform;
  double a = 0.0, b = 0.0;  // the type's two parameters, as listed above
};

const char* prior_name(PriorType t);
bool on_parameter_scale(PriorType t);  // a density of x (parameterScale*), not of theta
// type "" (empty cell) gives the undeclared default; parameters "a;b". Throws Error
// "<where>: ..." for an unknown type, a malformed pair, or a non-positive sd/scale/width.
Prior parse_prior(const std::string& type, const std::string& parameters, const std::string& where);
std::string format_prior_parameters(const Prior& p);  // "a;b" ("" when undeclared)

// The log density of the *scaled* value x that the samplers move: the prior's density of theta
// times |d theta / d x| for priors on theta, so that every scale describes the same belief.
// -inf outside the bounds [lower, upper] (linear scale) and where theta leaves the prior's
// support. Not renormalised for the truncation: the samplers need it only up to a constant.
double log_prior_density(const Prior& p, Scale s, double lower, double upper, double x);

}  // namespace phasmid::fit
