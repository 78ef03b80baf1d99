#include "scenario/kinds/analytic_kind.hpp"

#include <fmt/format.h>

#include "common/error.hpp"
#include "io/h5_file.hpp"
#include "io/trajectory_writer.hpp"

namespace phasmid::scenario::kinds {
namespace {

class AnalyticRun : public ScenarioRun {
 public:
  AnalyticRun(const model::ParameterSet& ps, std::vector<double> p, double y)
      : params_(ps), p_(std::move(p)), features_{{"y", y, "1"}} {}
  const std::vector<features::Feature>& features() const override { return features_; }
  void write(io::H5Writer& out) const override {
    io::write_parameters(out, params_, p_);
    features::write_features_h5(out, features_);
  }
  std::string summary() const override { return fmt::format("closed form, y = {:.10g}", features_[0].value); }

 private:
  const model::ParameterSet& params_;
  std::vector<double> p_;
  std::vector<features::Feature> features_;
};

class AnalyticScenario : public Scenario {
 public:
  explicit AnalyticScenario(AnalyticFunction f) : f_(std::move(f)) {}
  std::string kind() const override { return f_.kind; }
  model::ParameterSet& parameters() override { return f_.parameters; }
  bool takes_simulation_settings() const override { return false; }
  std::vector<features::FeatureInfo> feature_catalogue() const override {
    return {{"y", "1", false, f_.y_description}};
  }
  std::unique_ptr<ScenarioRun> run(const std::vector<double>& p, const RunSettings&) const override {
    if (p.size() != f_.parameters.size())
      throw Error(f_.kind + ": " + std::to_string(p.size()) + " parameter values for " +
                  std::to_string(f_.parameters.size()) + " parameters");
    return std::make_unique<AnalyticRun>(f_.parameters, p, f_.y(p));
  }
  std::unique_ptr<fit::ResidualProblem> make_fit(const fit::FitSpec&) const override {
    throw Error("model kind " + f_.kind + " is an analytic test function without data to fit ([fit] does not apply)");
  }

 private:
  AnalyticFunction f_;
};

}  // namespace

std::unique_ptr<Scenario> make_analytic_scenario(AnalyticFunction f) {
  return std::make_unique<AnalyticScenario>(std::move(f));
}

}  // namespace phasmid::scenario::kinds
