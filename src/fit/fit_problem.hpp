#pragma once
// A fit problem (Ceres' "Problem" + "CostFunction" in one): a model, the parameters to
// estimate (on their scales, within bounds) and the targets. evaluate() runs one simulation
// with forward sensitivities of the estimated parameters and returns the weighted residuals
// and their exact Jacobian with respect to the scaled parameters x. Cost = 1/2 sum r^2.
#include <atomic>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "features/features.hpp"
#include "features/model_step_cycle.hpp"
#include "fit/parameter_table.hpp"
#include "fit/residual_problem.hpp"
#include "fit/targets.hpp"
#include "model/ode_model.hpp"
#include "solver/simulator.hpp"

namespace phasmid::fit {

struct ProblemSettings {
  double t_end_ms = 0;     // 0: the latest time any target needs (at least one output)
  double discard_ms = 0;   // transient ignored by feature targets
  // Output of step-cycle comparisons: /fit/steps/<step_output_base + i>, with a "condition"
  // attribute when condition is set (fit/condition_problem.hpp).
  std::string condition;
  size_t step_output_base = 0;
  solver::SolverOptions solver;
  features::FeatureOptions feature_options;  // discard_ms overwritten by the field above
};

class FitProblem : public ResidualProblem {
 public:
  // `parameters` lists every parameter the fit touches; fixed ones (estimate = false) are
  // set to their nominal value. Throws Error for unknown names, parameters whose forward
  // sensitivities would be inexact (they move a switch time or the initial state), unknown
  // features or channels, and problems without targets. Offsets (kinematic time offsets in ms,
  // observable offsets in deg) are estimates that are no model parameter.
  FitProblem(const model::OdeModel& model, std::vector<FitParameter> parameters, Targets targets,
             ProblemSettings settings);

  std::string parameter_unit(size_t j) const override;
  std::vector<std::string> tied_parameters(size_t j) const override;  // '*' ids tie several
  // The model's full parameter vector for scaled estimates x.
  std::vector<double> model_parameters(const double* x) const;

  // Residuals r (num_residuals) and, if J != nullptr, dr/dx (row-major m x n). Returns false
  // (with the reason in *error) if the simulation fails or a feature cannot be computed.
  bool evaluate(const double* x, double* r, double* J, std::string* error = nullptr) const override;

  // /fit/model (kinematic comparison), /trajectory, /parameters, /features.
  void write_model_output(io::H5Writer& out, const double* x, bool usable, double output_dt_ms) const override;

  // /fit/steps/<i> alone (write_model_output writes it with the rest), for the conditions of a
  // ConditionsProblem after its first.
  void write_step_comparison(io::H5Writer& out, const double* x) const;

  // Central finite-difference Jacobian (row-major), for tests and benchmarks. Relative step h.
  bool jacobian_fd(const double* x, double* J, double h = 1e-6, std::string* error = nullptr) const;

  // A dense trajectory (dt ms) at x over the problem horizon, for output.
  solver::SolveResult simulate(const double* x, double dt_ms) const;

  // The model values compared with each kinematic target's samples (deg), per channel.
  struct KinematicComparison {
    std::vector<double> time_ms;  // data times (file time, without the offset)
    std::vector<std::string> channels;
    std::vector<std::vector<double>> data_deg, model_deg;
  };
  std::vector<KinematicComparison> kinematic_comparison(const double* x) const;

  // False when a target is a value-only feature (`gait_class`): then only derivative-free
  // optimisers apply.
  bool has_jacobian() const override { return value_only_feature_.empty(); }
  std::string no_jacobian_reason() const override;

  long evaluations() const { return evaluations_; }
  long jacobian_evaluations() const { return jacobian_evaluations_; }
  double horizon_ms(const double* x) const;
  const model::OdeModel& model() const { return model_; }
  const ProblemSettings& settings() const { return settings_; }

 private:
  struct Run;
  Run run(const double* x, bool with_sens) const;
  // The constructor's steps, in order; each throws Error on what it rejects.
  void check_parameters(const std::set<std::string>& offset_ids);
  void map_estimates(const std::set<std::string>& offset_ids);
  void label_targets();
  // Recording step cycles (fit_problem_steps.cpp): validate and label; residual rows; /fit/steps.
  void label_step_cycles();
  size_t step_cycle_rows(const solver::SolveResult& res, const double* x, bool sens, size_t row, double* r, std::vector<double>& dth) const;
  void write_step_cycles(io::H5Writer& out, const solver::SolveResult& res, const double* x) const;
  double offset_value(long est, double fixed, const double* x) const { return est >= 0 ? x[est] : fixed; }
  std::pair<long, double> observable_parameter(const std::string& id, double value, const std::string& origin,
                                               const char* what) const;

  const model::OdeModel& model_;
  Targets targets_;
  ProblemSettings settings_;
  std::vector<double> base_p_;
  // Per estimated parameter: model parameter index, or kinematic-target offset (kind).
  struct EstMap { bool is_model; std::vector<size_t> model_indices, sens_columns; std::string unit; };
  std::vector<EstMap> est_map_;
  std::vector<size_t> sens_params_;
  // Per kinematic target: index into est_ (or -1) of its offset and the fixed offset value.
  std::vector<long> offset_est_;
  std::vector<double> offset_fixed_;
  std::vector<size_t> switch_channel_, kin_channel_base_;
  std::vector<std::vector<size_t>> kin_channels_;  // per kinematic target: model angle channel per data channel
  // Per step-cycle target, per observable: model angle channel, data channel, offset, scale and
  // noise parameter (index of the estimate, or -1 and the fixed value; a fixed noise of 0: none)
  // and, for an estimated noise, the centre ln(sigma0) and span M of its residuals (noise_rows).
  struct StepCycleMap {
    std::vector<size_t> model_channel, data_channel;
    std::vector<long> offset_est, scale_est, sigma_est;
    std::vector<double> offset_fixed, scale_fixed, sigma_fixed, noise_centre, noise_span;
  };
  std::vector<StepCycleMap> step_maps_;
  size_t noise_rows(const StepCycleMap& m, size_t o, double sigma, size_t n_bins, size_t row, double* r,
                    std::vector<double>& dth) const;
  struct ObservableAt {
    size_t model_profile, data_channel;
    double offset, scale, sigma;  // sigma 0: per bin from the recording or the observable's sigma_deg
  };
  ObservableAt observable_at(const features::ModelStepCycle& mc, const StepCycleMap& m, size_t o, const double* x) const;
  double theta_value(long est, double fixed, const double* x) const {
    return est >= 0 ? from_scaled(est_[static_cast<size_t>(est)].scale, x[est]) : fixed;
  }
  std::map<std::string, std::string> offset_units_;  // non-model estimates: id -> unit
  std::set<std::string> noise_ids_;                 // those that are an observable's noise (any scale)
  std::string value_only_feature_;                 // first target without gradients (empty: none)
  mutable std::atomic<long> evaluations_{0}, jacobian_evaluations_{0};
};

}  // namespace phasmid::fit
