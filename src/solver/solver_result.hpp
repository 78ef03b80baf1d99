#pragma once
// What one integration returns (Simulator::run, solver/simulator.hpp): the outputs, the located
// events, the command times the model's triggers resolved, and the integrators' counters.
#include <chrono>
#include <cstddef>
#include <ctime>
#include <vector>

namespace phasmid::solver {

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
  // Brian2's standalone runs report around their network run (docs/performance.md).
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

}  // namespace phasmid::solver
