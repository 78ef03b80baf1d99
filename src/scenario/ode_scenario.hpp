#pragma once
// The scenario of every model that is one ODE system (model::OdeModel): runs integrate it with
// CVODES (solver::Simulator), features come from located events (features/features.hpp), the
// trajectory is written as docs/hdf5.md describes, and forward sensitivities, Floquet
// multipliers and fits with exact Jacobians are available through ode_model().
#include <memory>

#include "model/ode_model.hpp"
#include "scenario/scenario.hpp"

namespace phasmid::scenario {

class OdeScenario : public Scenario {
 public:
  // `defaults`: the kind's settings where the config's [simulation] says nothing (the
  // integrator and tolerances the method study chose: docs/performance.md).
  explicit OdeScenario(std::unique_ptr<model::OdeModel> model, RunSettings defaults = {})
      : model_(std::move(model)), defaults_(std::move(defaults)) {}
  RunSettings default_settings() const override { return defaults_; }

  std::string kind() const override { return model_->kind(); }
  model::ParameterSet& parameters() override { return model_->parameters(); }
  std::vector<features::FeatureInfo> feature_catalogue() const override {
    return features::feature_catalogue(*model_);
  }
  std::unique_ptr<ScenarioRun> run(const std::vector<double>& p, const RunSettings& settings) const override;
  std::vector<features::Feature> evaluate_features(const std::vector<double>& p,
                                                   const RunSettings& settings) const override;
  std::vector<std::pair<std::string, std::string>> run_time_parameters() const override;
  std::unique_ptr<fit::ResidualProblem> make_fit(const fit::FitSpec& spec) const override;
  const model::OdeModel* ode_model() const override { return model_.get(); }

  // Hands the model over (tests and benchmarks that drive the solver directly).
  std::unique_ptr<model::OdeModel> release_model() { return std::move(model_); }

 private:
  std::unique_ptr<model::OdeModel> model_;
  RunSettings defaults_;
};

}  // namespace phasmid::scenario
