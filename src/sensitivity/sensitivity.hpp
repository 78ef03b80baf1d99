#pragma once
// Forward sensitivity analysis of a model's trajectory and gait features (docs/sensitivity.md):
// CVODES forward sensitivities (exact df/dp and J s from the templated right-hand side),
// feature sensitivities from event times (implicit-function formula), normalised
// sensitivities and a ranking per feature; or the same by central finite differences.
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "features/features.hpp"
#include "model/ode_model.hpp"
#include "solver/simulator.hpp"

namespace phasmid::io {
class H5Writer;
}

namespace phasmid::sensitivity {

enum class Method { Forward, FiniteDifference };
Method parse_method(const std::string& s);  // "forward" | "fd"; throws Error otherwise
const char* method_name(Method m);

struct SensitivityOptions {
  std::vector<std::string> parameters;  // names; empty: every parameter of the model
  double t_end_ms = 2000.0;
  double output_dt_ms = 1.0;
  double discard_ms = 0.0;              // transient ignored by the features
  Method method = Method::Forward;
  solver::SolverOptions solver;
  bool write_trajectory = true;         // keep the time x state x parameter sensitivities
  double fd_relative_step = 1e-4;       // h = fd_relative_step * max(|p|, fd_min_scale)
  double fd_min_scale = 1e-8;
  features::FeatureOptions feature_options;  // discard_ms is overwritten by the field above
  // Forward runs differentiate this many parameters each (independent runs; the numbers depend
  // on the chunks, never on the threads), on `threads` threads (0: OpenMP's default).
  size_t chunk_parameters = 16;
  int threads = 0;
};

struct SensitivityReport {
  Method method = Method::Forward;
  // State tolerances of the run(s) and, for forward runs, the factor on the sensitivity
  // tolerances (SensitivityOptions::solver.sensitivity_tolerance_factor; [sensitivity] tolerance_factor).
  double rtol = 0.0, atol = 0.0, tolerance_factor = 1.0;
  std::vector<std::string> parameters, parameter_units;
  std::vector<double> parameter_values;
  // How each column was obtained: "forward" or "fd".
  std::vector<std::string> parameter_method;
  std::vector<features::Feature> features;  // nominal values
  Eigen::MatrixXd absolute;  // features x parameters: dF/dp (feature unit per parameter unit)
  Eigen::MatrixXd relative;  // features x parameters: p/F dF/dp (NaN where F == 0)
  std::vector<std::vector<std::string>> ranking;  // per feature: parameter names by |relative|, largest first

  // Trajectory sensitivities (empty unless write_trajectory): n_time x n_states x n_params, row-major.
  std::vector<double> time;
  std::vector<std::string> state_names, state_units;
  std::vector<double> trajectory;
  std::vector<double> states;  // nominal trajectory, n_time x n_states

  double wall_seconds = 0.0;
  solver::SolverStats stats;  // of the nominal (forward: with sensitivities) run
  long fd_runs = 0;           // simulations done for finite differences

  size_t feature_index(const std::string& name) const;  // throws Error if absent
  double trajectory_sens(size_t k, size_t i, size_t j) const {
    return trajectory[(k * state_names.size() + i) * parameters.size() + j];
  }
};

// The indices of the parameters named (empty: every parameter but the command times that
// [[triggers]] set, which are functions of the others). Throws Error naming an unknown or a
// triggered parameter, or when none is left.
std::vector<size_t> select_parameters(const model::OdeModel& model, const std::vector<std::string>& names);

// Fills `relative` (p/F dF/dp, NaN where F == 0) and `ranking` from `absolute`, the features
// and the parameter values.
void rank_parameters(SensitivityReport& report);

// A report's header: method, tolerances, and name, unit, value and method of each parameter
// in `idx` (the columns of every matrix to come).
SensitivityReport report_header(const model::OdeModel& model, const std::vector<double>& p,
                                const std::vector<size_t>& idx, const SensitivityOptions& options);

// Calls run(k, begin, end) for each chunk k of columns [begin, end) of count columns, in
// chunks of options.chunk_parameters, on options.threads threads (each call on its own
// thread; they must not share mutable state), with a progress line per finished chunk when
// options.solver.progress and there is more than one chunk. Returns the number of chunks; none
// without columns. An exception in a call is rethrown once the calls in flight have returned.
size_t for_each_chunk(size_t count, const SensitivityOptions& options,
                      const std::function<void(size_t chunk, size_t begin, size_t end)>& run);

SensitivityReport analyse_sensitivities(const model::OdeModel& model, std::vector<double> p,
                                        const SensitivityOptions& options);

// /sensitivity/{parameters, parameter_units, parameter_values, parameter_method,
// features/<f>, units/<f>, relative/<f>, ranking/<f>, feature_values, [time, state_names,
// state_units, trajectory]} (docs/sensitivity.md).
void write_sensitivity_h5(io::H5Writer& out, const SensitivityReport& report);

}  // namespace phasmid::sensitivity
