#pragma once
// The whole-system driver (AMICI's "Solver"), kept apart from the model: one run() that
// integrates an OdeModel over output times, locates events by root finding, and optionally
// integrates forward sensitivities with respect to chosen parameters. Its options are
// solver/solver_options.hpp, its result solver/solver_result.hpp; plain runs of a model with
// parts go to the partitioned driver (solver/partitioned_simulator.hpp).
#include <string>
#include <vector>

#include "model/ode_model.hpp"
#include "solver/solver_options.hpp"
#include "solver/solver_result.hpp"

namespace phasmid::solver {

// The output times of a run: a caller's list (referred to, not copied), or the evenly spaced
// grid of output_grid() computed on demand, so that a long run holds no list of its times.
class OutputTimes {
 public:
  OutputTimes(const std::vector<double>& list) : list_(&list), n_(list.size()) {}  // implicit: any list
  static OutputTimes grid(double t_end, double dt);
  size_t size() const { return n_; }
  bool empty() const { return n_ == 0; }
  double operator[](size_t k) const { return list_ ? (*list_)[k] : k < n_grid_ ? k * dt_ : t_end_; }
  double front() const { return (*this)[0]; }
  double back() const { return (*this)[n_ - 1]; }
  std::vector<double> to_vector() const;

 private:
  OutputTimes() = default;
  const std::vector<double>* list_ = nullptr;
  size_t n_ = 0, n_grid_ = 0;  // grid: k * dt for k < n_grid_, then t_end
  double dt_ = 0.0, t_end_ = 0.0;
};

class Simulator {
 public:
  // Throws phasmid::Error naming the option when options.validate() does.
  Simulator(const model::OdeModel& model, SolverOptions options = {});
  // Integrates from t = 0 with the model's initial state for parameter vector p.
  // Throws SolverError (with time and CVODES flag) when the integrator fails.
  // The model's triggers (OdeModel::triggers) resolve their command times during the run:
  // p's values for those parameters are ignored (see SolveResult::commands). Sensitivities
  // include how the triggered times move with p (d t_event / dp at the event, a jump at the
  // command time); a triggered command time in sens_params is an Error (docs/sensitivity.md).
  SolveResult run(const std::vector<double>& p, const OutputTimes& output_times,
                  const std::vector<RootSpec>& roots = {}, const std::vector<size_t>& sens_params = {}) const;
  SolveResult run(const std::vector<double>& p, const std::vector<double>& output_times,
                  const std::vector<RootSpec>& roots = {}, const std::vector<size_t>& sens_params = {}) const {
    return run(p, OutputTimes(output_times), roots, sens_params);
  }
  const SolverOptions& options() const { return options_; }

 private:
  const model::OdeModel& model_;
  SolverOptions options_;
};

// Evenly spaced output times 0, dt, ..., t_end (t_end included).
std::vector<double> output_grid(double t_end, double dt);

// Dense Jacobian df/dy at (t, y) from the templated right-hand side (column-major n x n).
std::vector<double> jacobian_autodiff(const model::OdeModel& model, double t, const std::vector<double>& y,
                                      const std::vector<double>& p);
// The same Jacobian as the KLU path computes it: structural pattern sampled around the initial
// state, columns coloured so that columns sharing no row are differentiated together
// (n_colors: how many directions that takes instead of n). Dense column-major, for tests.
std::vector<double> jacobian_sparse_autodiff(const model::OdeModel& model, double t, const std::vector<double>& y,
                                             const std::vector<double>& p, size_t* n_colors = nullptr);

// OdeModelPart::compile for a run that asks for it (SolverOptions::compiled_rhs); a part that
// cannot be compiled (or a model without parts: nullptr) stays generic, with one warning per
// process on stderr.
void compile_if_asked(model::OdeModelPart* part, const SolverOptions& options);

}  // namespace phasmid::solver
