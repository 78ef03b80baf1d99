#pragma once
// The options of one integration (Simulator, solver/simulator.hpp) and their one check,
// SolverOptions::validate, in the style of Ceres' Solver::Options::IsValid: every caller (the
// config layer, the Python module, the simulator itself) goes through it, and its messages name
// the option ("solver option 'rtol' must be in (0, 1), got 2"), never a config section; the
// config layer adds its file:line.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace phasmid::solver {

class OutputSink;  // solver/output_sink.hpp

// Auto: dense up to kDenseMaxStates states, KLU (sparse) above, where the sparse factorisation
// is the faster at equal step counts (docs/performance.md "Naive setups").
enum class LinearSolverKind { Auto, Dense, Band, Klu };
constexpr size_t kDenseMaxStates = 40;
// With forward sensitivities every corrector iteration solves one linear system per parameter,
// so the dense back-substitutions weigh more and KLU pays off at fewer states.
constexpr size_t kDenseMaxStatesWithSensitivities = 16;
enum class SensitivityMethod { Staggered, Simultaneous };
// CVODES BDF with Newton (stiff), or Dormand-Prince 5(4) in phasmid's own stepper
// (solver/dopri_session.hpp: no Jacobian, no linear solves, six right-hand sides per step).
// Chosen per model kind by measurement (docs/solver.md "Integrators"); sensitivities always run
// on CVODES BDF.
enum class IntegratorKind { Bdf, Dopri5 };
inline bool is_explicit_rk(IntegratorKind k) { return k == IntegratorKind::Dopri5; }
// On: one integrator per joint network (model::PartitionGrain::Joints). Neurons: also each
// network's spiking cells apart from the stiff network that drives them (PartitionGrain::Neurons).
enum class Partitioning { Off, On, Neurons };
// Why Partitioning::Neurons refuses threads >= 2 (docs/solver.md "Integrators").
inline constexpr const char* kNeuronsOnOneThread =
    "the windowed driver would extrapolate the presynaptic potentials over its window";
// The limits validate() holds the thread count and per-unit tolerances to.
inline constexpr int kMaxThreads = 256;

struct SolverOptions {
  double rtol = 1e-8;
  double atol = 1e-8;
  long max_steps = 1000000;          // per output interval
  double max_step_ms = 0.0;          // 0: no limit
  IntegratorKind integrator = IntegratorKind::Bdf;
  LinearSolverKind linear_solver = LinearSolverKind::Auto;
  // Simultaneous: at the same cost as staggered, more accurate feature sensitivities on the
  // networks (docs/sensitivity.md); `staggered = true` in [sensitivity] selects the other.
  SensitivityMethod sensitivity_method = SensitivityMethod::Simultaneous;
  bool sensitivity_error_control = true;
  // Sensitivity tolerances: rtolS = factor * rtol, atolS_j = factor * atol / pbar_j with
  // pbar_j = |p_j| (factor 1 = CVodeSensEEtolerances). Only with error control on.
  double sensitivity_tolerance_factor = 1.0;
  // Copy the sensitivities at every output time into SolveResult::s (off: only at events,
  // which is all the features need; saves CVodeGetSens and memory on a fine output grid).
  bool sensitivities_at_outputs = true;
  // Plain runs (no sensitivities) of a model with several parts (joints): one integrator per
  // part, each on its own step size (solver/partitioned_simulator.hpp). Off: one system. The
  // model kind chooses (scenario/kinds/integration.hpp); the simulator runs what it is given.
  Partitioning partitioning = Partitioning::Off;
  // Partitioning::Neurons with an explicit integrator: the parts the model marks stiff
  // (ModelPartition::stiff) run CVODES BDF at rtol = atol = stiff_part_tol; the rest run the
  // explicit method at rtol, atol. 1e-7: the loosest that keeps the single joint's period
  // within 0.002 ms of the reference (docs/solver.md "Spiking cells apart").
  double stiff_part_tol = 1e-7;
  // Plain runs: each part's double right-hand side compiled for it at the run's start
  // (OdeModelPart::compile, model/compiled_rhs.hpp; cached, so once per model per machine),
  // the same values at less cost. Where a model cannot, a warning and the generic evaluation.
  bool compiled_rhs = false;
  // Partitioned runs only. 1: the sequential scheduler (the part furthest behind steps next).
  // >= 2: the parts step concurrently on that many threads in windows of window_ms, each
  // reading the others' angles from their polynomials at the window's start; the result
  // depends on window_ms, never on the thread count or timing
  // (solver/partitioned_simulator.hpp).
  int threads = 1;
  // Absolute tolerance by the unit of a state (StateInfo::unit: "mV", "1", "rad", ...) in place
  // of atol; states of other units keep atol. Runs without sensitivities only.
  std::vector<std::pair<std::string, double>> atol_by_unit;
  // The same for the stiff parts of Partitioning::Neurons (in place of stiff_part_tol as their
  // atol; their rtol stays stiff_part_tol): a 60 mV potential at atol 1e-7 is held to far more
  // digits than the features need.
  std::vector<std::pair<std::string, double>> stiff_part_atol_by_unit;
  // 0.25-1 ms are as accurate on the three legs; 4 ms is not (docs/solver.md "Run loop").
  double window_ms = 1.0;
  bool progress = false;             // progress line on a terminal (stderr)
  // Set: output samples go to the sink as they are reached instead of into SolveResult
  // (plain runs without sensitivities; see SolveResult::t).
  OutputSink* output_sink = nullptr;
  std::string progress_label = "simulate";

  // True when every field is in its range and the fields agree with each other; otherwise
  // false with *error (if given) a one-line message naming the option and its limit.
  bool is_valid(std::string* error) const;
  // Throws phasmid::Error with is_valid's message.
  void validate() const;
};

}  // namespace phasmid::solver
