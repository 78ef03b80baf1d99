#pragma once
// The scenario of every model that is one ODE system (model::OdeModel): runs integrate it with
// CVODES (solver::Simulator), features come from located events (features/features.hpp), the
// trajectory is written as docs/hdf5.md describes, and forward sensitivities, Floquet
// multipliers and fits with exact Jacobians are available through ode_model().
#include <memory>

#include "model/ode_model.hpp"
#include "scenario/kinds/integration.hpp"
#include "scenario/scenario.hpp"

namespace phasmid::scenario {

class OdeScenario : public Scenario {
 public:
  // `integration`: how the kind integrates a request (Scenario::integration; the kinds'
  // policies, scenario/kinds/integration.hpp); by default one system on CVODES BDF.
  explicit OdeScenario(std::unique_ptr<model::OdeModel> model,
                       kinds::Integration integration = kinds::whole_system_bdf())
      : model_(std::move(model)), integration_(std::move(integration)) {}
  solver::SolverOptions integration(const IntegrationRequest& request) const override {
    return integration_(request);
  }

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
  kinds::Integration integration_;
};

}  // namespace phasmid::scenario
