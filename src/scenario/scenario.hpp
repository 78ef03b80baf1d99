#pragma once
// A scenario: one model of any kind with its named parameters, ready to run (compare AMICI's
// Model, which every analysis takes). Every verb works through this interface — simulate,
// params, sweep, fit and report on every kind; sensitivity where the kind is an ODE system —
// so that no analysis knows which model it drives. Model kinds make scenarios from the
// [model] section of a config (scenario/registry.hpp).
//
// Contract:
//  - parameters() holds every number of the model (name, unit, source, admissible range);
//    run(p, ...) takes a full parameter vector in that order and never changes the scenario,
//    so one scenario may run many parameter vectors (sweeps, fits), one thread each.
//  - A run that fails (integration failure, impossible state) throws phasmid::Error or
//    solver::SolverError with a one-line reason.
//  - ScenarioRun::write() writes /trajectory, /parameters and /features (and any group the
//    kind adds, e.g. /events) in the layout of docs/hdf5.md; the caller writes the run info.
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "features/features.hpp"
#include "model/parameters.hpp"
#include "solver/simulator.hpp"

namespace phasmid::io {
class H5Writer;
}
namespace phasmid::model {
class OdeModel;
}
namespace phasmid::fit {
class ResidualProblem;
struct FitSpec;
}  // namespace phasmid::fit

namespace phasmid::scenario {

// What a user asked of the integration: [simulation] rtol, atol, max_step_ms, integrator and
// [simulation.expert] of a config, or the Python module's simulate() keywords (docs/config.md).
// An empty optional is "not given": the model kind decides (Scenario::integration).
struct IntegrationRequest {
  std::optional<double> rtol, atol, max_step_ms;
  std::optional<solver::IntegratorKind> integrator;  // empty: "auto"
  // [simulation.expert]
  std::optional<solver::Partitioning> partitioning;
  std::optional<int> threads;
  std::optional<double> window_ms;
  std::optional<bool> compiled_rhs;
  std::optional<solver::LinearSolverKind> linear_solver;
  std::optional<double> network_tol;  // SolverOptions::stiff_part_tol
  std::optional<std::vector<std::pair<std::string, double>>> atol_by_unit, network_atol_by_unit;
};

// How long to run and how to integrate ([simulation] of a config; docs/config.md).
struct RunSettings {
  double t_end_ms = 9000.0;
  double output_dt_ms = 1.0;
  double discard_ms = 0.0;  // transient ignored by gait features
  solver::SolverOptions solver;
};

// The outcome of one run: features, and whatever the kind writes to HDF5.
class ScenarioRun {
 public:
  virtual ~ScenarioRun() = default;
  virtual const std::vector<features::Feature>& features() const = 0;
  // /trajectory, /parameters, /features, ... (not the root attributes).
  virtual void write(io::H5Writer& out) const = 0;
  // Lines worth showing on the terminal after the run (resolved trigger times, warnings).
  virtual std::vector<std::string> notes() const { return {}; }
  // One line: what was run and how long it took (states, simulated ms, wall seconds).
  virtual std::string summary() const = 0;
  // The integrated trajectory of kinds that are one ODE system (nullptr for others), for
  // callers that hand its arrays on without copying (the Python module, docs/python.md).
  virtual const solver::SolveResult* solution() const { return nullptr; }
};

class Scenario {
 public:
  virtual ~Scenario() = default;
  virtual std::string kind() const = 0;  // the registered kind name ("single_joint", "cruse1980")
  virtual model::ParameterSet& parameters() = 0;
  const model::ParameterSet& parameters() const { return const_cast<Scenario*>(this)->parameters(); }

  // The kind's integration for what the user asked (docs/solver.md "How each kind
  // integrates"): every SolverOptions field the run reads, resolved (parts, method and
  // tolerances per part, compiled right-hand side). The one place a kind's defaults live;
  // throws Error naming the option where the request combines settings the kind refuses.
  // Kinds that take no [simulation] (takes_simulation_settings false) integrate nothing.
  virtual solver::SolverOptions integration(const IntegrationRequest&) const { return {}; }
  // Settings where the config has no [simulation] section: run times' defaults, integration({}).
  RunSettings default_settings() const {
    RunSettings s;
    s.solver = integration({});
    return s;
  }
  // Whether [simulation] applies to this kind (false: the kind's own parameters set its run).
  virtual bool takes_simulation_settings() const { return true; }

  // Every feature a run can report: name, unit, whether it has a derivative with respect to
  // the parameters, and what it means (docs/features.md).
  virtual std::vector<features::FeatureInfo> feature_catalogue() const = 0;

  virtual std::unique_ptr<ScenarioRun> run(const std::vector<double>& p, const RunSettings& settings) const = 0;
  // Features only (sweeps, fits without trajectories): the same values run(p).features() gives.
  virtual std::vector<features::Feature> evaluate_features(const std::vector<double>& p,
                                                           const RunSettings& settings) const {
    return run(p, settings)->features();
  }

  // Parameters whose value is set during a run rather than given (e.g. command times resolved
  // by [[triggers]]), with what sets them; `phasmid params` shows them so.
  virtual std::vector<std::pair<std::string, std::string>> run_time_parameters() const { return {}; }

  // The residual problem of a fit (docs/fit.md) whose spec the config layer read from [fit]
  // (config::fit_spec); it refers to this scenario (keep it alive). Throws Error naming the
  // spec's origins (file:line) where the spec does not fit the model.
  virtual std::unique_ptr<fit::ResidualProblem> make_fit(const fit::FitSpec& spec) const = 0;

  // The ODE system behind the scenario, for analyses that need one (forward sensitivities,
  // Floquet multipliers, fits with exact Jacobians); nullptr for kinds that are not ODEs.
  virtual const model::OdeModel* ode_model() const { return nullptr; }
  model::OdeModel* ode_model() { return const_cast<model::OdeModel*>(std::as_const(*this).ode_model()); }
};

}  // namespace phasmid::scenario
