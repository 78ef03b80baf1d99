#pragma once
// Forward sensitivities with jump conditions at switch times that depend on the parameters
// (prescribed switching periods, times of central commands) and with initial states that
// depend on the parameters.
//
// The run is split at the model's breakpoints tau_k. Each segment integrates the shifted
// state x = y - S_k (p - pbar), where S_k are the state sensitivities entering the segment,
// so the solver's zero initial sensitivities are right and s_y = s_x + S_k. At a switch
//   s(tau+) = s(tau-) + (f(tau-) - f(tau+)) dtau/dp
// (the state is continuous, the right-hand side jumps, the switch time moves with p).
// dtau/dp and dy0/dp come from central differences of the algebraic functions
// breakpoints() and initial_state().
#include <vector>

#include "model/ode_model.hpp"
#include "solver/simulator.hpp"

namespace phasmid::sensitivity {

// Same contract as solver::Simulator::run with sensitivities.
solver::SolveResult run_with_switch_sensitivities(const model::OdeModel& model, const std::vector<double>& p,
                                                  const std::vector<double>& output_times,
                                                  const std::vector<solver::RootSpec>& roots,
                                                  const std::vector<size_t>& sens_params,
                                                  const solver::SolverOptions& options);

}  // namespace phasmid::sensitivity
