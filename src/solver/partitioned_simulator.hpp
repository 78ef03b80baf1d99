#pragma once
// Partitioned (multirate) integration of a plain run: one CVODES integrator per part of the
// model (model::ModelPartition: for the walking networks, one joint's CPGs, interneurons,
// motoneurons, muscles and mechanics), each on its own step size. Parts read each other only
// through joint angles (the sensory and intersegmental sigmoids), which a part takes from the
// other part's interpolating polynomial of its last step (CVodeGetDky: the Nordsieck
// polynomial, extrapolated over at most one step of the reading part).
//
// Why: one integrator for the whole body steps at the pace of the fastest event in any joint
// (a half-centre switch, a motoneuron spike), so its step count grows with the number of
// joints and each step costs the whole system. Parts step only for their own events.
//
// Scheduling keeps the extrapolation short and the interpolation valid: the part that lags
// furthest behind takes the next step, so every other part's last step covers the lagging
// part's current time. Central commands (model breakpoints) are synchronisation points where
// all parts restart together. Events (roots) belong to the part owning the root's state; the
// other parts' states at the event are interpolated once they have passed its time.
// [[triggers]]: their crossings fire in time order once every part has passed them; a command
// time found so becomes a synchronisation point, and parts already beyond it go back to it.
//
// On several threads (SolverOptions::threads >= 2) the parts step concurrently in windows of
// SolverOptions::window_ms: each reads the others only from copies of their polynomials taken
// at the window's start, and records each step's end values and derivatives
// (solver/step_history.hpp), by which its states at the others' events, at outputs and at
// roll-backs are found after the window; the polynomial the others read next is taken once, at
// its last step in the window. Without triggers the windows lie on a fixed grid and a part may
// complete later windows as soon as the parts it reads have completed the ones before, while
// another part is still behind (kWindowLookAhead windows at most); with triggers, whose
// commands send parts back, every part completes one window before any starts the next. The
// numbers depend on the windows, not on the thread count or timing; threads = 1 is the
// scheduler above.
//
// Not for forward sensitivities (Simulator::run then integrates the whole model as one
// system); SolverOptions::partitioning chooses (docs/solver.md).
//
// Files: partitioned_parts.hpp (the parts and their sessions), partitioned_driver.hpp (the
// driver: events, outputs, triggers, roll-backs in partitioned_simulator.cpp) and one file
// per scheduler: partitioned_sequential.cpp, partitioned_windowed.cpp, partitioned_grid.cpp.
#include <vector>

#include "model/ode_model.hpp"
#include "solver/simulator.hpp"  // OutputTimes, SolverOptions, SolveResult

namespace phasmid::solver {

// The absolute tolerance of each of `states` (global indices): SolverOptions::atol_by_unit
// by the state's unit, SolverOptions::atol for the others.
std::vector<double> state_atol(const model::OdeModel& model, const SolverOptions& options,
                               const std::vector<size_t>& states);
// Throws unless every unit of SolverOptions::atol_by_unit is a unit of some state of the model:
// a unit no state has would silently change nothing ("rad/ms" for velocities in rad/s).
void check_atol_units(const model::OdeModel& model, const SolverOptions& options);

SolveResult run_partitioned(const model::OdeModel& model, const model::ModelPartition& partition,
                            const SolverOptions& options, const std::vector<double>& p,
                            const OutputTimes& output_times, const std::vector<RootSpec>& roots);

}  // namespace phasmid::solver
