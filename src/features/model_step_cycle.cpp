#include "features/model_step_cycle.hpp"

#include <algorithm>

#include "common/error.hpp"
#include "common/units.hpp"
#include "features/feature_parts.hpp"

namespace phasmid::features {
namespace {
using detail::Dual;

// The angle state of channel c at time t (deg), linearly interpolated between outputs, with
// the derivative of that interpolant for a time that itself moves with p (dt).
Dual angle_at(const solver::SolveResult& res, size_t state, const Dual& t, size_t ns, bool with_grad) {
  const auto& T = res.t;
  auto it = std::lower_bound(T.begin(), T.end(), t.v);
  if (it == T.begin() || it == T.end()) throw Error("internal: step time " + std::to_string(t.v) + " ms outside the outputs");
  const size_t k = static_cast<size_t>(it - T.begin());
  const double h = T[k] - T[k - 1], w = (t.v - T[k - 1]) / h;
  const double y0 = res.state(k - 1, state), y1 = res.state(k, state);
  Dual a{((1 - w) * y0 + w * y1) * units::kDegPerRad, Eigen::VectorXd::Zero(ns)};
  if (with_grad)
    for (size_t j = 0; j < ns; ++j)
      a.g[j] = ((1 - w) * res.sens(k - 1, state, j) + w * res.sens(k, state, j) + (y1 - y0) / h * t.g[j]) * units::kDegPerRad;
  return a;
}

}  // namespace

ModelStepCycle model_step_cycle(const model::OdeModel& model, const solver::SolveResult& res, const std::string& leg,
                                int bins, const FeatureOptions& opt, bool with_grad) {
  if (!model.contact_leg(leg)) throw Error(leg + ": the model has no ground contact for this leg");
  const size_t ns = with_grad ? res.sens_params.size() : 0;
  const detail::ContactTimes c = detail::contact_times(model, res, opt, with_grad, feature_roots(model), leg);
  ModelStepCycle m;
  for (size_t i = 0; i < model.angles().size(); ++i)
    if (model.angles()[i].leg == leg) m.channels.push_back(i);
  for (int k = 0; k < bins; ++k) m.phase.push_back((k + 0.5) / bins);
  std::vector<std::vector<Dual>> sum(m.channels.size(), std::vector<Dual>(bins, Dual{0, Eigen::VectorXd::Zero(ns)}));
  Dual period{0, Eigen::VectorXd::Zero(ns)}, duty = period;
  for (size_t i = 0; i + 1 < c.touchdown.size(); ++i) {
    const Dual& td = c.touchdown[i];
    auto lo = std::find_if(c.liftoff.begin(), c.liftoff.end(), [&](const Dual& x) { return x.v > td.v; });
    if (lo == c.liftoff.end() || lo->v >= c.touchdown[i + 1].v) continue;
    const Dual T = c.touchdown[i + 1] - td;
    period = period + T;
    duty = duty + (*lo - td) / T;
    for (size_t ch = 0; ch < m.channels.size(); ++ch)
      for (int k = 0; k < bins; ++k)
        sum[ch][k] = sum[ch][k] +
                     angle_at(res, model.angles()[m.channels[ch]].angle_state, td + detail::scaled(T, m.phase[k]), ns, with_grad);
    ++m.steps;
  }
  if (m.steps == 0)
    throw Error(leg + ": the model made no complete step (touch-down, lift-off, touch-down) after " +
                std::to_string(opt.discard_ms) + " ms; lengthen t_end_ms");
  const double inv = 1.0 / static_cast<double>(m.steps);
  m.period_ms = period.v * inv, m.dperiod_ms = period.g * inv;
  m.duty_factor = duty.v * inv, m.dduty_factor = duty.g * inv;
  for (size_t ch = 0; ch < m.channels.size(); ++ch) {
    m.mean_deg.emplace_back();
    m.dmean_deg.emplace_back();
    for (int k = 0; k < bins; ++k) {
      m.mean_deg[ch].push_back(sum[ch][k].v * inv);
      if (with_grad) m.dmean_deg[ch].push_back(sum[ch][k].g * inv);
    }
  }
  return m;
}

}  // namespace phasmid::features
