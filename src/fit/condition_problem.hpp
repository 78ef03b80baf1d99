#pragma once
// Several experimental conditions of one model (PEtab's condition table): trials that share
// some parameters (the mechanics) and differ in others (drives, time scales). A Condition maps
// model parameters to a fit parameter of its own or to a fixed value; targets name their
// condition (StepCycleTarget::condition; the others belong to the model as configured, the
// condition ""). Each condition is a FitProblem of the model with its parameters so mapped;
// the ConditionsProblem stacks their residuals, and a fit parameter several conditions use gets
// the Jacobian columns of each in its rows. docs/recordings.md, "Several trials".
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "fit/fit_problem.hpp"

namespace phasmid::fit {

struct Condition {
  std::string id;                                     // "trial_a"
  std::map<std::string, std::string> parameter_ids;   // model parameter (or pattern) -> fit parameter id
  std::map<std::string, double> values;               // model parameter (or pattern) -> fixed value
  std::string origin;                                 // config file:line
};

class ConditionsProblem : public ResidualProblem {
 public:
  // Throws Error (one line) for a target naming an undefined condition, a condition no target
  // uses, a mapped fit parameter missing from `parameters`, or what a condition's FitProblem
  // refuses (prefixed with the condition).
  ConditionsProblem(const model::OdeModel& model, const std::vector<FitParameter>& parameters, const Targets& targets,
                    const ProblemSettings& settings, const std::vector<Condition>& conditions);

  std::string parameter_unit(size_t j) const override;
  std::vector<std::string> tied_parameters(size_t j) const override;
  bool has_jacobian() const override;
  std::string no_jacobian_reason() const override;
  // The conditions are evaluated in parallel (OpenMP); residuals in the order of the conditions.
  bool evaluate(const double* x, double* r, double* J, std::string* error = nullptr) const override;
  // The first condition's model as FitProblem writes it (/trajectory, /parameters, /features,
  // /fit/steps/...), every other condition's step-cycle comparisons numbered on, and each
  // condition's mapping under /fit/conditions/<id> (docs/hdf5.md).
  void write_model_output(io::H5Writer& out, const double* x, bool usable, double output_dt_ms) const override;

  size_t num_conditions() const { return parts_.size(); }
  const FitProblem& condition_problem(size_t c) const { return *parts_[c].problem; }

 private:
  struct Part {
    std::string id;
    std::unique_ptr<FitProblem> problem;
    std::vector<size_t> columns;  // per estimate of the part: its index in est_
    size_t first_row = 0;
    std::vector<std::string> mapped, fit_ids;  // the condition's model parameters and their fit ids ("" fixed)
    std::vector<double> fixed;
  };
  std::vector<double> part_x(const Part& p, const double* x) const;
  std::vector<Part> parts_;
};

}  // namespace phasmid::fit
