#pragma once
// Sensitivity of an event time and of the state at the event (implicit-function theorem).
// An event is a zero of g(y(t; p)) with g(y) = y[state] - level, so
//   dt*/dp = -(dg/dy . s) / (dg/dy . f) = -s[state] / f[state],
// and a quantity y_i read at the event has total derivative  s_i + f_i dt*/dp.
#include <Eigen/Dense>

#include "solver/simulator.hpp"

namespace phasmid::features {

// d t* / d p_j for every sensitivity parameter j (ms per parameter unit). Throws Error when
// the crossing is tangential (f[state] == 0), where the event time is not differentiable.
Eigen::VectorXd event_time_sensitivity(const solver::Event& event, const solver::RootSpec& root, size_t n_sens);

// d y_i(t*(p); p) / d p_j = s_ij + f_i dt*/dp_j.
Eigen::VectorXd state_at_event_sensitivity(const solver::Event& event, size_t i, const Eigen::VectorXd& dt_dp);

}  // namespace phasmid::features
