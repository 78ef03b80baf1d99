#pragma once
// When the right-hand side of a run switches, and what the sensitivities do there: one
// schedule per run, used by the whole-system and the partitioned driver.
//
//  - Stops: the model's central commands (OdeModel::breakpoints) strictly inside (0, t_end),
//    sorted, then t_end. The integrators restart at each stop but the last.
//  - Triggered command times (model::CommandTrigger): "never" (model::kUnresolvedMs) in p()
//    until their threshold crossing fires (TriggerTracker). Each trigger watches its threshold
//    as a root in both directions, after the caller's roots (roots()). A command time found so
//    is one more stop (add_command_time), unless one lies within 1e-9 (relative) of it.
//  - Switch-time sensitivities: d tau / dp_j of every stop, from central differences of the
//    breakpoints (exact: switch times are algebraic functions of the parameters), and of a
//    triggered command time (crossing_time_sensitivity: the implicit-function theorem at the
//    crossing; the delay is constant). At tau the state is continuous and the sensitivities
//    jump: s(tau+) = s(tau-) + (f(tau-) - f(tau+)) d tau / dp_j (apply_jump). Two switches at
//    one time that move differently with p have no single jump: an Error.
#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "model/ode_model.hpp"
#include "solver/run_parameters.hpp"
#include "solver/simulator.hpp"
#include "solver/trigger_tracker.hpp"

namespace phasmid::solver {

// g(p + h e_k), g(p - h e_k) and h = 1e-6 max(1, |p_k|): a central difference along p_k of a
// function that is algebraic in the parameters (initial states, switch times), so exact up to
// round-off.
template <class G>
auto central_pair(const std::vector<double>& p, size_t k, G g) {
  const double h = 1e-6 * std::max(1.0, std::abs(p[k]));
  std::vector<double> pp = p, pm = p;
  pp[k] += h;
  pm[k] -= h;
  return std::make_tuple(g(pp), g(pm), h);
}

class CommandSchedule {
 public:
  // Throws Error if a triggered command time is in sens_params (it is not a free parameter).
  CommandSchedule(const model::OdeModel& model, const std::vector<double>& p_given, double t_end,
                  const std::vector<size_t>& sens_params);

  // The parameters with the triggered command times resolved so far.
  const std::vector<double>& p() const { return p_.values(); }
  // Their owner, for the drivers to register what mirrors them (RunParameters::bind, mirror).
  RunParameters& parameters() { return p_; }
  // The caller's roots followed by one per trigger (its threshold, both directions).
  std::vector<RootSpec> roots(const std::vector<RootSpec>& caller) const;
  const std::vector<model::CommandTrigger>& triggers() const { return model_.triggers(); }

  double next_stop() const { return stops_[next_]; }
  bool last_stop() const { return next_ + 1 == stops_.size(); }
  // d tau / dp_j of the next stop (zero where it does not move with p_j).
  const std::vector<double>& next_stop_jump() const { return dtau_[next_]; }
  void pass_stop() { ++next_; }
  double t_end() const { return stops_.back(); }

  // A crossing of trigger k's threshold at t in direction dir, y the full state there. If it
  // fires the trigger, its targets take t + delay in p() (and in every mirror of parameters()),
  // are appended to `commands`, and the result is true.
  bool fire(size_t k, double t, int dir, const double* y, std::vector<ResolvedCommand>& commands);
  // d t_event / dp_j of trigger k's crossing at t, from the crossing state's rate of change
  // `rate` (f of the trigger's state) and its sensitivities s_state[j]. Throws Error for a
  // tangential crossing (rate 0: the time is not differentiable).
  std::vector<double> crossing_time_sensitivity(size_t k, double t, double rate,
                                                const std::vector<double>& s_state) const;
  // Folds trigger k's d tau / dp into `into`, the jump of a switch at the same time.
  void merge_jump(std::vector<double>& into, const std::vector<double>& dtau_dp, size_t k) const;

  enum class Added { Existing, Later, Next };
  // The command time tau (< t_end) of trigger k as a stop with its d tau / dp (empty without
  // sensitivities): merged into an existing stop within 1e-9, or a new stop, Next if it is now
  // the next one.
  Added add_command_time(double tau, const std::vector<double>& dtau_dp, size_t k);

  // The sensitivities s[j] (n values each) at a switch at tau with d tau / dp_j = dtau_dp[j],
  // y the state there: s += (f(tau-) - f(tau+)) dtau_dp[j].
  void apply_jump(double tau, const std::vector<double>& dtau_dp, const double* y, const std::vector<double*>& s) const;

 private:
  void stop_time_sensitivities();

  const model::OdeModel& model_;
  RunParameters p_;
  std::vector<size_t> sens_params_;
  std::vector<double> stops_;
  std::vector<std::vector<double>> dtau_;  // per stop, per sensitivity parameter
  size_t next_ = 0;
  std::vector<TriggerTracker> trackers_;
};

}  // namespace phasmid::solver
