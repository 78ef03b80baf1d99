#include "fit/prior.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "common/error.hpp"

namespace phasmid::fit {

namespace {
struct PriorName {
  PriorType type;
  const char* name;
};
constexpr PriorName kPriorNames[] = {
    {PriorType::ParameterScaleUniform, "parameterScaleUniform"},
    {PriorType::ParameterScaleNormal, "parameterScaleNormal"},
    {PriorType::ParameterScaleLaplace, "parameterScaleLaplace"},
    {PriorType::Uniform, "uniform"},
    {PriorType::Normal, "normal"},
    {PriorType::Laplace, "laplace"},
    {PriorType::LogNormal, "logNormal"},
    {PriorType::LogLaplace, "logLaplace"},
};

double parse_number(const std::string& s, const std::string& where) {
  try {
    size_t used = 0;
    const double v = std::stod(s, &used);
    if (used == s.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  throw Error(where + ": objectivePriorParameters: '" + s + "' is not a finite number");
}

constexpr double kLogSqrt2Pi = 0.91893853320467274178;  // ln sqrt(2 pi)

// Log density of value v under the type's own law (v is x for parameterScale*, theta else).
double log_density(const Prior& p, double v) {
  const double inf = std::numeric_limits<double>::infinity();
  switch (p.type) {
    case PriorType::ParameterScaleUniform:
    case PriorType::Uniform:
      return (v >= p.a && v <= p.b) ? -std::log(p.b - p.a) : -inf;
    case PriorType::ParameterScaleNormal:
    case PriorType::Normal: {
      const double z = (v - p.a) / p.b;
      return -0.5 * z * z - std::log(p.b) - kLogSqrt2Pi;
    }
    case PriorType::ParameterScaleLaplace:
    case PriorType::Laplace:
      return -std::abs(v - p.a) / p.b - std::log(2.0 * p.b);
    case PriorType::LogNormal: {
      if (!(v > 0)) return -inf;
      const double z = (std::log(v) - p.a) / p.b;
      return -0.5 * z * z - std::log(p.b * v) - kLogSqrt2Pi;
    }
    case PriorType::LogLaplace:
      if (!(v > 0)) return -inf;
      return -std::abs(std::log(v) - p.a) / p.b - std::log(2.0 * p.b * v);
  }
  return -inf;
}
}  // namespace

bool on_parameter_scale(PriorType t) {
  return t == PriorType::ParameterScaleUniform || t == PriorType::ParameterScaleNormal ||
         t == PriorType::ParameterScaleLaplace;
}

const char* prior_name(PriorType t) {
  for (const auto& n : kPriorNames)
    if (n.type == t) return n.name;
  return "?";
}

Prior parse_prior(const std::string& type, const std::string& parameters, const std::string& where) {
  Prior p;
  if (type.empty()) {
    if (!parameters.empty()) throw Error(where + ": objectivePriorParameters without objectivePriorType");
    return p;
  }
  bool known = false;
  for (const auto& n : kPriorNames)
    if (type == n.name) p.type = n.type, known = true;
  if (!known) {
    std::string all;
    for (const auto& n : kPriorNames) all += (all.empty() ? "" : ", ") + std::string(n.name);
    throw Error(where + ": objectivePriorType '" + type + "' is not one of " + all);
  }
  const size_t semi = parameters.find(';');
  if (semi == std::string::npos || parameters.find(';', semi + 1) != std::string::npos)
    throw Error(where + ": objectivePriorParameters of " + type + " must be two numbers 'a;b', got '" + parameters + "'");
  p.a = parse_number(parameters.substr(0, semi), where);
  p.b = parse_number(parameters.substr(semi + 1), where);
  const bool width = p.type == PriorType::Uniform || p.type == PriorType::ParameterScaleUniform;
  if (width && !(p.b > p.a)) throw Error(where + ": " + type + " prior needs lower < upper, got '" + parameters + "'");
  if (!width && !(p.b > 0)) throw Error(where + ": " + type + " prior needs a positive second parameter (sd or scale), got '" + parameters + "'");
  p.declared = true;
  return p;
}

std::string format_prior_parameters(const Prior& p) {
  if (!p.declared) return "";
  std::ostringstream os;
  os.precision(17);
  os << p.a << ';' << p.b;
  return os.str();
}

double log_prior_density(const Prior& p, Scale s, double lower, double upper, double x) {
  const double inf = std::numeric_limits<double>::infinity();
  // Bounds compared on the scale, as the optimisers' box is: exp(log(10)) is not 10.
  const double lo = to_scaled(s, lower), hi = to_scaled(s, upper);
  if (!(x >= lo && x <= hi)) return -inf;
  if (!p.declared) return -std::log(hi - lo);
  if (on_parameter_scale(p.type)) return log_density(p, x);
  return log_density(p, from_scaled(s, x)) + std::log(dtheta_dx(s, x));
}

}  // namespace phasmid::fit
