#include "solver/command_schedule.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace phasmid::solver {

namespace {

// p with every triggered command time "never" until its event (no breakpoint, command off).
// A command time set by a trigger is a function of the other parameters (the event time plus
// a constant delay), not a free parameter: there is no sensitivity to it.
std::vector<double> with_triggers_unresolved(const model::OdeModel& model, std::vector<double> p,
                                             const std::vector<size_t>& sens_params) {
  for (const auto& tr : model.triggers())
    for (size_t q : tr.targets) {
      if (std::find(sens_params.begin(), sens_params.end(), q) != sens_params.end())
        throw Error("no sensitivity to " + model.parameters().at(q).name + ": it is set by the [[triggers]] event " +
                    tr.event + " (give it a fixed value to differentiate by it)");
      p[q] = model::kUnresolvedMs;
    }
  return p;
}

}  // namespace

CommandSchedule::CommandSchedule(const model::OdeModel& model, const std::vector<double>& p_given, double t_end,
                                 const std::vector<size_t>& sens_params)
    : model_(model),
      p_(with_triggers_unresolved(model, p_given, sens_params)),
      sens_params_(sens_params),
      trackers_(model.triggers().size()) {
  stops_ = model.breakpoints(p(), t_end);
  std::sort(stops_.begin(), stops_.end());
  stops_.erase(std::remove_if(stops_.begin(), stops_.end(), [&](double b) { return b <= 0.0 || b >= t_end; }),
               stops_.end());
  stops_.push_back(t_end);
  dtau_.assign(stops_.size(), std::vector<double>(sens_params.size(), 0.0));
  stop_time_sensitivities();
}

// dtau_[b][j] by central differences of the breakpoints, matched to the nominal ones by value.
void CommandSchedule::stop_time_sensitivities() {
  const double t_end = stops_.back();
  auto nearest = [](const std::vector<double>& v, double x) {
    double best = NAN;
    for (double b : v)
      if (std::isnan(best) || std::abs(b - x) < std::abs(best - x)) best = b;
    return best;
  };
  for (size_t j = 0; j < sens_params_.size(); ++j) {
    auto [bp, bm, hstep] = central_pair(p(), sens_params_[j], [&](const std::vector<double>& q) {
      return model_.breakpoints(q, t_end);
    });
    std::sort(bp.begin(), bp.end());
    std::sort(bm.begin(), bm.end());
    for (size_t b = 0; b + 1 < stops_.size(); ++b) {
      // The perturbed switch nearest to the nominal one is the same switch as long as it
      // moved by less than a quarter of the gap to the neighbouring switches.
      double gap = stops_[b + 1] - stops_[b];
      if (b > 0) gap = std::min(gap, stops_[b] - stops_[b - 1]);
      const double up = nearest(bp, stops_[b]), dn = nearest(bm, stops_[b]);
      if (std::abs(up - stops_[b]) > 0.25 * gap || std::abs(dn - stops_[b]) > 0.25 * gap) continue;
      dtau_[b][j] = (up - dn) / (2 * hstep);
    }
  }
}

std::vector<RootSpec> CommandSchedule::roots(const std::vector<RootSpec>& caller) const {
  std::vector<RootSpec> all = caller;
  for (const auto& tr : model_.triggers()) all.push_back({tr.state, tr.level_scale * p()[tr.level_param], 0});
  return all;
}

bool CommandSchedule::fire(size_t k, double t, int dir, const double* y, std::vector<ResolvedCommand>& commands) {
  const model::CommandTrigger& tr = model_.triggers()[k];
  if (!trackers_[k].fires(tr, t, dir, p(), y)) return false;
  const double when = t + tr.delay_ms;
  p_.set(tr.targets, when);
  for (size_t q : tr.targets) commands.push_back({q, when, k});
  return true;
}

std::vector<double> CommandSchedule::crossing_time_sensitivity(size_t k, double t, double rate,
                                                               const std::vector<double>& s_state) const {
  const model::CommandTrigger& tr = model_.triggers()[k];
  if (rate == 0.0 || !std::isfinite(rate))
    throw Error("trigger " + tr.event + " at t = " + std::to_string(t) +
                " ms is a tangential crossing: its time is not differentiable");
  // g = y[state] - scale p[level] stays 0 along the crossing: dg/dt d t_event + dg/dp_j = 0.
  std::vector<double> dte(sens_params_.size());
  for (size_t j = 0; j < sens_params_.size(); ++j)
    dte[j] = -(s_state[j] - (sens_params_[j] == tr.level_param ? tr.level_scale : 0.0)) / rate;
  return dte;
}

void CommandSchedule::merge_jump(std::vector<double>& into, const std::vector<double>& dtau_dp, size_t k) const {
  for (size_t j = 0; j < dtau_dp.size(); ++j) {
    if (into[j] != 0.0 && std::abs(into[j] - dtau_dp[j]) > 1e-9 * std::max(1.0, std::abs(dtau_dp[j])))
      throw Error("trigger " + model_.triggers()[k].event + ": its command time coincides with another switch that " +
                  "moves differently with " + model_.parameters().at(sens_params_[j]).name +
                  " (no single sensitivity jump)");
    into[j] = dtau_dp[j];
  }
}

CommandSchedule::Added CommandSchedule::add_command_time(double tau, const std::vector<double>& dtau_dp, size_t k) {
  const auto first = stops_.begin() + static_cast<long>(next_);
  const auto at = std::lower_bound(first, stops_.end(), tau);
  const double tol = 1e-9 * std::max(1.0, std::abs(tau));
  auto existing = stops_.end();
  if (at != stops_.end() && std::abs(*at - tau) <= tol) existing = at;
  else if (at != first && std::abs(*(at - 1) - tau) <= tol) existing = at - 1;
  if (existing != stops_.end()) {
    merge_jump(dtau_[static_cast<size_t>(existing - stops_.begin())], dtau_dp, k);
    return Added::Existing;
  }
  const auto b = at - stops_.begin();
  const Added added = at == first ? Added::Next : Added::Later;
  stops_.insert(at, tau);
  dtau_.insert(dtau_.begin() + b, std::vector<double>(sens_params_.size(), 0.0));
  merge_jump(dtau_[static_cast<size_t>(b)], dtau_dp, k);
  return added;
}

void CommandSchedule::apply_jump(double tau, const std::vector<double>& dtau_dp, const double* y,
                                 const std::vector<double*>& s) const {
  if (std::all_of(dtau_dp.begin(), dtau_dp.end(), [](double v) { return v == 0.0; })) return;
  const size_t n = model_.num_states();
  std::vector<double> f_before(n), f_after(n);
  const double delta = 1e-9 * std::max(1.0, std::abs(tau));  // one-sided limits at the switch
  model_.rhs(tau - delta, y, p().data(), f_before.data());
  model_.rhs(tau + delta, y, p().data(), f_after.data());
  for (size_t j = 0; j < dtau_dp.size(); ++j)
    if (dtau_dp[j] != 0.0)
      for (size_t i = 0; i < n; ++i) s[j][i] += (f_before[i] - f_after[i]) * dtau_dp[j];
}

}  // namespace phasmid::solver
