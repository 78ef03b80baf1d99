#include "sweep/sweep_spec.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace phasmid::sweep {

std::vector<std::string> SweepSpec::names() const {
  std::vector<std::string> v;
  for (auto& p : parameters) v.push_back(p.name);
  return v;
}
std::vector<std::string> SweepSpec::units() const {
  std::vector<std::string> v;
  for (auto& p : parameters) v.push_back(p.unit);
  return v;
}

double map_unit(const SweptParameter& p, double u) {
  double x = p.log_scale ? std::exp(std::log(p.lower) + u * (std::log(p.upper) - std::log(p.lower)))
                         : p.lower + u * (p.upper - p.lower);
  return std::min(std::max(x, p.lower), p.upper);  // rounding never leaves [lower, upper]
}

void set_unit_points(SweepSpec& spec, const std::vector<double>& unit) {
  const std::size_t dim = spec.parameters.size();
  if (dim == 0 || unit.size() % dim != 0)
    throw Error("sweep: " + std::to_string(unit.size()) + " unit-cube values are not whole rows of " + std::to_string(dim) +
                " parameters");
  if (!spec.options.empty()) throw Error("sweep: explicit points cannot be combined with [[sweep.option]]");
  spec.n_design = unit.size() / dim;
  spec.n_combos = 1;
  spec.n_points = spec.n_design;
  spec.points.resize(unit.size());
  for (std::size_t i = 0; i < unit.size(); ++i) spec.points[i] = map_unit(spec.parameters[i % dim], unit[i]);
}

std::size_t SweepSpec::option_value(std::size_t combo, std::size_t k) const {
  std::size_t rest = combo;
  for (std::size_t j = options.size(); j-- > k + 1;) rest /= options[j].labels.size();
  return rest % options[k].labels.size();
}

std::string SweepSpec::describe_combo(std::size_t combo) const {
  std::string s;
  for (std::size_t k = 0; k < options.size(); ++k)
    s += (s.empty() ? "" : ", ") + options[k].name + " = " + options[k].labels[option_value(combo, k)];
  return s;
}

}  // namespace phasmid::sweep
