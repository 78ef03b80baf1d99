#pragma once
// The parameter vector of one run and its one owner (CommandSchedule holds it): the values the
// right-hand sides read, and everything that mirrors them: the model parts bound to them
// (OdeModelPart::bind gathers their neurons' parameters once) and the Jet copies that
// Jacobians and sensitivities evaluate with. A triggered command time is written through
// set(), which brings every mirror into step; the drivers never write the values themselves.
#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

#include "model/ode_model.hpp"

namespace phasmid::solver {

class RunParameters {
 public:
  explicit RunParameters(std::vector<double> values) : values_(std::move(values)) {}
  RunParameters(const RunParameters&) = delete;  // mirrors refer to this object's values
  RunParameters& operator=(const RunParameters&) = delete;

  const std::vector<double>& values() const { return values_; }

  // `part` bound to the values now and again after every set(); it must outlive this object's
  // last set() (the run).
  void bind(model::OdeModelPart* part) {
    part->bind(values_.data());
    parts_.push_back(part);
  }

  // `jets` becomes the values as Jets (derivative lanes zero) and is kept in step by set();
  // between evaluations its lanes must be zero again.
  template <class J>
  void mirror(std::vector<J>& jets) {
    jets.clear();
    for (double v : values_) jets.emplace_back(v);
    mirrors_.push_back([&jets](size_t q, double v) { jets[q] = J(v); });
  }

  // Parameters `qs` take `value`; then every mirror and bound part.
  void set(const std::vector<size_t>& qs, double value) {
    for (size_t q : qs) values_[q] = value;
    for (const auto& m : mirrors_)
      for (size_t q : qs) m(q, value);
    for (model::OdeModelPart* part : parts_) part->bind(values_.data());
  }

 private:
  std::vector<double> values_;
  std::vector<model::OdeModelPart*> parts_;
  std::vector<std::function<void(size_t, double)>> mirrors_;
};

}  // namespace phasmid::solver
