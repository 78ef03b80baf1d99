#pragma once
// CVODES driver (AMICI's "Solver"), kept apart from the model: options struct with defaults,
// one run() that integrates an OdeModel over output times, locates events by root finding,
// and optionally integrates forward sensitivities with respect to chosen parameters.
#include <chrono>
#include <ctime>
#include <string>
#include <vector>

#include "model/ode_model.hpp"

namespace phasmid::solver {

class OutputSink;  // solver/output_sink.hpp

// Auto: dense up to kDenseMaxStates states, KLU (sparse) above, where the sparse factorisation
// is the faster at equal step counts (measured in bench/results).
enum class LinearSolverKind { Auto, Dense, Band, Klu };
constexpr size_t kDenseMaxStates = 40;
// With forward sensitivities every corrector iteration solves one linear system per parameter,
// so the dense back-substitutions weigh more and KLU pays off at fewer states
// (bench/results, "Linear solver and Jacobian").
constexpr size_t kDenseMaxStatesWithSensitivities = 16;
enum class JacobianKind { AutoDiff, FiniteDifference };
enum class SensitivityMethod { Staggered, Simultaneous };
// Sensitivity right-hand sides J s_j + df/dp_j: all parameters at once in Jet<8> chunks (one
// model evaluation per 8 parameters) or one Jet<1> evaluation per parameter.
enum class SensitivityRhs { Batched, PerParameter };
// CVODES BDF + Newton (stiff) or Adams-Moulton + fixed-point iteration (non-stiff: no
// Jacobian, no linear solves), or an explicit adaptive Runge-Kutta pair of ARKODE's ERKStep
// (Bogacki-Shampine 3(2), Dormand-Prince 5(4), Verner 6(5), Fehlberg 8(7)): no Jacobian, no
// linear solves, a few right-hand sides per step; Dopri5 is Dormand-Prince 5(4) in phasmid's
// own stepper (solver/dopri_session.hpp), ARKODE's method with less work per step. Chosen by
// measurement per model (bench/results, "Method study"); sensitivities always run on
// CVODES BDF.
enum class IntegratorKind { Bdf, Adams, ErkBs3, ErkDp5, ErkVerner65, ErkFehlberg78, Dopri5 };
inline bool is_explicit_rk(IntegratorKind k) { return k != IntegratorKind::Bdf && k != IntegratorKind::Adams; }
enum class VectorKernels { Phasmid, Sundials };
// On: one integrator per joint network (model::PartitionGrain::Joints). Neurons: also each
// network's spiking cells apart from the stiff network that drives them (PartitionGrain::Neurons).
enum class Partitioning { Auto, On, Off, Neurons };
// Why Partitioning::Neurons refuses threads >= 2 (docs/solver.md "Integrators").
inline constexpr const char* kNeuronsOnOneThread =
    "the windowed driver would extrapolate the presynaptic potentials over its window";

struct SolverOptions {
  double rtol = 1e-8;
  double atol = 1e-8;
  long max_steps = 1000000;          // per output interval
  double max_step_ms = 0.0;          // 0: no limit
  IntegratorKind integrator = IntegratorKind::Bdf;
  LinearSolverKind linear_solver = LinearSolverKind::Auto;
  JacobianKind jacobian = JacobianKind::AutoDiff;
  // Simultaneous: at the same cost as staggered, more accurate feature sensitivities on the
  // networks (bench/results, "After the compiled kernels"); `staggered = true` in
  // [sensitivity] selects the other.
  SensitivityMethod sensitivity_method = SensitivityMethod::Simultaneous;
  SensitivityRhs sensitivity_rhs = SensitivityRhs::Batched;
  bool sensitivity_error_control = true;
  // Sensitivity tolerances: rtolS = factor * rtol, atolS_j = factor * atol / pbar_j with
  // pbar_j = |p_j| (factor 1 = CVodeSensEEtolerances). Only with error control on.
  double sensitivity_tolerance_factor = 1.0;
  // Per-state factor on atolS (empty: 1 for every state). A large factor takes that state's
  // sensitivity out of the error test while the others stay in it (CVodeSensSVtolerances).
  std::vector<double> sensitivity_atol_scale;
  // Copy the sensitivities at every output time into SolveResult::s (off: only at events,
  // which is all the features need; saves CVodeGetSens and memory on a fine output grid).
  bool sensitivities_at_outputs = true;
  // Vector and matrix arithmetic and the dense LU: phasmid's compiled kernels
  // (solver/serial_kernels.hpp, solver/matrix_kernels.hpp; Debian's libsundials is built
  // without optimisation) or the library's own (bench/results).
  VectorKernels vector_kernels = VectorKernels::Phasmid;
  int max_order = 0;                      // BDF/Adams order limit (0: CVODES default, 5 / 12)
  bool stability_limit_detection = false; // CVodeSetStabLimDet (BDF orders >= 3)
  // Plain runs (no sensitivities) of a model with several parts (joints): one integrator per
  // part, each on its own step size (solver/partitioned_simulator.hpp). Auto: where the model
  // says it pays at equal accuracy (OdeModel::partition_by_default: the rate-MN walking models;
  // bench/results "Partitioned integration").
  Partitioning partitioning = Partitioning::Auto;
  // Partitioning::Neurons with an explicit integrator: the parts the model marks stiff
  // (ModelPartition::stiff) run CVODES BDF at rtol = atol = stiff_part_tol; the rest run the
  // explicit method at rtol, atol. 1e-7: the study's loosest that keeps the single joint's
  // period within 0.002 ms of the reference (bench/results "Spiking cells apart").
  double stiff_part_tol = 1e-7;
  // Plain runs: each part's double right-hand side compiled for it at the run's start
  // (OdeModelPart::compile, model/compiled_rhs.hpp; cached, so once per model per machine),
  // the same values at less cost. Where a model cannot, a warning and the generic evaluation.
  bool compiled_rhs = false;
  // Partitioned runs only. 1: the sequential scheduler (the part furthest behind steps next).
  // >= 2: the parts step concurrently on that many threads in windows of window_ms, each
  // reading the others' angles from their polynomials at the window's start, extrapolated at
  // most window_order beyond their last step; the result depends on window_ms and
  // window_order, never on the thread count or timing (solver/partitioned_simulator.hpp).
  int threads = 1;
  // Absolute tolerance by the unit of a state (StateInfo::unit: "mV", "1", "rad", ...) in place
  // of atol; states of other units keep atol. Runs without sensitivities only.
  std::vector<std::pair<std::string, double>> atol_by_unit;
  // The same for the stiff parts of Partitioning::Neurons (in place of stiff_part_tol as their
  // atol; their rtol stays stiff_part_tol). A 60 mV potential at atol 1e-7 is held to far more
  // digits than the features need: `mV = 1e-4` takes 8 % fewer instructions on the single
  // joint at the same accuracy (bench/results "The network part's absolute tolerance").
  std::vector<std::pair<std::string, double>> stiff_part_atol_by_unit;
  double window_ms = 1.0;  // 0.25-1 ms are as accurate on the three legs; 4 ms is not (bench/results)
  int window_order = 3;
  // Windowed runs without triggers: a part may complete up to this many windows ahead of the
  // slowest, while a thread would otherwise wait (0: never). Changes no number.
  int window_look_ahead = 16;
  bool window_look_ahead_always = false;  // tests: step ahead even where no thread would wait
  bool progress = false;             // progress line on a terminal (stderr)
  // Set: output samples go to the sink as they are reached instead of into SolveResult
  // (plain runs without sensitivities; see SolveResult::t).
  OutputSink* output_sink = nullptr;
  std::string progress_label = "simulate";
};

// Root function g(y) = y[state] - level; an event is a zero crossing in `direction`
// (+1 rising, -1 falling, 0 both).
struct RootSpec {
  size_t state;
  double level;
  int direction;
};

struct Event {
  double t;                 // ms
  size_t root;              // index into the RootSpec list
  int direction;            // +1 rising, -1 falling
  std::vector<double> y;    // state at the event
  std::vector<double> ydot; // right-hand side at the event (for event-time sensitivities)
  std::vector<double> s;    // state sensitivities at the event, n_states x n_sens (row-major)
};

struct SolverStats {
  long steps = 0, rhs_evals = 0, jac_evals = 0, sens_rhs_evals = 0, restarts = 0;
  // Over the whole run (CVodeReInit at breakpoints resets CVODES' own counters): error-test
  // failures, Newton iterations and convergence failures, linear-solver setups.
  long error_test_failures = 0, newton_iterations = 0, newton_failures = 0, linear_setups = 0;
  long integrators = 1;  // parts integrated separately (SolverOptions::partitioning), 1: one system
  double wall_seconds = 0.0;
  // CPU time of the process over the same span (std::clock: all its threads), the clock that
  // Brian2's standalone runs report around their network run (bench/results).
  double cpu_seconds = 0.0;
};

// The wall and process CPU time of a solve, from construction to stop(), as SolverStats keeps
// them (both drivers time the same span: schedule, integration and output).
class SolveTimer {
 public:
  void stop(SolverStats& s) const {
    s.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0_).count();
    s.cpu_seconds = static_cast<double>(std::clock() - cpu0_) / CLOCKS_PER_SEC;
  }

 private:
  std::chrono::steady_clock::time_point wall0_ = std::chrono::steady_clock::now();
  std::clock_t cpu0_ = std::clock();
};

// A command time resolved by a model trigger during the run (model::CommandTrigger).
struct ResolvedCommand {
  size_t parameter;  // index of the command-time parameter
  double t_ms;       // the value it was given: event time + delay
  size_t trigger;    // index into model.triggers()
};

struct SolveResult {
  // Output times (ms). With SolverOptions::output_sink the samples went to the sink: t holds
  // only the last output time (the end of the analysed window) and y, s, steps_at_output are empty.
  std::vector<double> t;
  std::vector<double> y;    // n_out x n_states, row-major
  std::vector<double> s;    // n_out x n_states x n_sens, row-major (empty without sensitivities
                            // or with SolverOptions::sensitivities_at_outputs off: see Event::s)
  std::vector<size_t> sens_params;
  std::vector<Event> events;
  std::vector<ResolvedCommand> commands;  // in the order the triggers fired
  std::vector<long> steps_at_output;  // cumulative solver steps at each output time (diagnostics)
  SolverStats stats;
  size_t n_states = 0;
  double state(size_t k, size_t i) const { return y[k * n_states + i]; }
  double sens(size_t k, size_t i, size_t j) const {
    return s[(k * n_states + i) * sens_params.size() + j];
  }
};

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
