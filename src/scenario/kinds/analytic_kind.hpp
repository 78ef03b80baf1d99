#pragma once
// Analytic test functions as model kinds (docs/gsa.md, "Test models"): a scenario whose only
// feature `y` is a closed-form function of its parameters, so that `phasmid gsa` (or sweep)
// runs them exactly as it runs the walking model — config, registry, sweep engine, HDF5 —
// and their known sensitivity indices check the whole chain. No time, no trajectory:
// [simulation] does not apply, and a run writes /parameters and /features only.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "scenario/registry.hpp"

namespace phasmid::scenario::kinds {

struct AnalyticFunction {
  std::string kind;                  // registry name
  model::ParameterSet parameters;    // every input and coefficient, with unit and source
  std::string y_description;         // the catalogue line of feature `y`
  std::function<double(const std::vector<double>& p)> y;  // p in parameters' order
};

std::unique_ptr<Scenario> make_analytic_scenario(AnalyticFunction f);

}  // namespace phasmid::scenario::kinds
