// Features of every angle channel and the derived 0/1 features; the per-leg gait features are
// in leg_features.cpp (feature_parts.hpp lists the files).
#include "features/features.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "common/units.hpp"
#include "features/event_time.hpp"
#include "features/feature_parts.hpp"
#include "model/leg_tables.hpp"

namespace phasmid::features {
namespace {

using detail::Dual;
using detail::DualFeature;
using detail::mean;
using detail::scaled;

struct Extremum {
  bool is_max;
  Dual t;      // ms
  Dual angle;  // deg
};

// Extrema of one channel in time order, after the transient, with wiggles removed.
std::vector<Extremum> channel_extrema(const model::AngleChannel& ch, size_t root_index, const solver::RootSpec& root,
                                      const solver::SolveResult& res, const FeatureOptions& opt, bool with_grad) {
  const size_t ns = with_grad ? res.sens_params.size() : 0;
  std::vector<Extremum> ex;
  // Events before the discard time take part in the turning-point selection below (so that the
  // first extremum after it is judged against the swing that precedes it, not taken as a turning
  // point only because nothing precedes it: a pause of the angle in mid-swing just after
  // discard_ms would otherwise count as a minimum) but are dropped from the result.
  for (const auto& e : res.events) {
    if (e.root != root_index) continue;
    Extremum x;
    x.is_max = e.direction < 0;  // velocity falls through zero at a maximum
    x.t.v = e.t;
    x.angle.v = e.y.at(ch.angle_state) * units::kDegPerRad;
    x.t.g = Eigen::VectorXd::Zero(ns);
    x.angle.g = Eigen::VectorXd::Zero(ns);
    if (with_grad && e.t >= opt.discard_ms) {
      x.t.g = event_time_sensitivity(e, root, ns);
      x.angle.g = state_at_event_sensitivity(e, ch.angle_state, x.t.g) * units::kDegPerRad;
    }
    ex.push_back(std::move(x));
  }
  // Keep the turning points of the gait cycle only (peak detection with hysteresis, as in
  // Billauer's peakdet): a maximum counts once the angle has fallen more than `delta` below
  // it, a minimum once it has risen more than `delta` above it. Damped oscillations around
  // an equilibrium within one phase are thereby skipped, and an extremum the run ends on
  // before it is confirmed is dropped.
  double lo = INFINITY, hi = -INFINITY;  // range after the transient sets the hysteresis
  for (auto& x : ex) {
    if (x.t.v < opt.discard_ms) continue;
    lo = std::min(lo, x.angle.v);
    hi = std::max(hi, x.angle.v);
  }
  if (!(hi >= lo)) return {};
  const double delta = std::max(opt.min_swing_deg, opt.min_swing_fraction * (hi - lo));
  std::vector<Extremum> kept;
  int looking = 0;  // 0: undecided, +1: looking for a maximum, -1: for a minimum
  size_t imax = 0, imin = 0;
  for (size_t k = 0; k < ex.size(); ++k) {
    const double v = ex[k].angle.v;
    if (ex[k].is_max && (looking >= 0) && (v > ex[imax].angle.v || !ex[imax].is_max)) imax = k;
    if (!ex[k].is_max && (looking <= 0) && (v < ex[imin].angle.v || ex[imin].is_max)) imin = k;
    if (looking >= 0 && ex[imax].is_max && v < ex[imax].angle.v - delta) {
      kept.push_back(ex[imax]);
      looking = -1;
      imin = k;
    } else if (looking <= 0 && !ex[imin].is_max && v > ex[imin].angle.v + delta) {
      kept.push_back(ex[imin]);
      looking = +1;
      imax = k;
    }
  }
  kept.erase(std::remove_if(kept.begin(), kept.end(), [&](const Extremum& x) { return x.t.v < opt.discard_ms; }),
             kept.end());
  return kept;
}

// Derived 0/1 features, present at every run (not omitted like the others), so that a global
// sensitivity analysis can take the probability of a rhythm or a gait (docs/features.md):
// `oscillates` when the first channel has a period over the window; with three contact legs
// `is_tripod` / `is_tetrapod` when gait_class is 2 / 1 (0 where it is irregular or undefined).
// Classes, piecewise constant in the parameters: zero gradient.
void derived_features(const model::OdeModel& model, bool oscillates, size_t ns, std::vector<DualFeature>& out) {
  if (model.angles().empty()) return;
  auto indicator = [&](bool on) { return Dual{on ? 1.0 : 0.0, Eigen::VectorXd::Zero(ns)}; };
  out.push_back({"oscillates", indicator(oscillates), "1"});
  if (!detail::has_three_contact_legs(model)) return;
  double gait = 0;
  for (const DualFeature& f : out)
    if (f.name == "gait_class") gait = f.value.v;
  out.push_back({"is_tripod", indicator(gait == 2), "1"});
  out.push_back({"is_tetrapod", indicator(gait == 1), "1"});
}

std::vector<DualFeature> compute(const model::OdeModel& model, const solver::SolveResult& res,
                                 const FeatureOptions& opt, bool with_grad) {
  const size_t ns = with_grad ? res.sens_params.size() : 0;
  if (with_grad && ns == 0)
    throw Error("feature gradients need a run with sensitivities");
  std::vector<solver::RootSpec> roots = feature_roots(model);
  std::vector<DualFeature> out;
  bool have_global = false;
  std::vector<Dual> ref_max;  // maxima of the first channel (reference for phase lags)
  Dual ref_period;
  bool have_ref = false;
  for (size_t c = 0; c < model.angles().size(); ++c) {
    const auto& ch = model.angles()[c];
    const std::string pre = ch.leg + "." + ch.joint + ".";
    model::JointNaming nm = model::joint_naming(model::parse_joint(ch.joint));
    std::vector<Extremum> ex = channel_extrema(ch, opt.root_offset + c, roots[c], res, opt, with_grad);

    std::vector<Dual> t_max, t_min, a_max, a_min, inc, dec;
    for (size_t k = 0; k < ex.size(); ++k) {
      (ex[k].is_max ? t_max : t_min).push_back(ex[k].t);
      (ex[k].is_max ? a_max : a_min).push_back(ex[k].angle);
      if (k + 1 < ex.size()) (ex[k].is_max ? dec : inc).push_back(ex[k + 1].t - ex[k].t);
    }
    if (t_max.size() >= 2) {
      Dual period = scaled(t_max.back() - t_max.front(), 1.0 / (t_max.size() - 1));
      out.push_back({pre + "period_ms", period, "ms"});
      if (!have_global) {
        out.insert(out.begin(), {"period_ms", period, "ms"});
        have_global = true;
      }
      if (!inc.empty()) out.push_back({pre + nm.phase_inc + "_fraction", mean(inc, ns) / period, "1"});
    }
    if (c == 0 && t_max.size() >= 2) {
      ref_max = t_max;
      ref_period = scaled(t_max.back() - t_max.front(), 1.0 / (t_max.size() - 1));
      have_ref = true;
    }
    if (c > 0 && have_ref && !t_max.empty()) {
      // Phase lag: time from the latest maximum of the first channel to each maximum of this
      // one, in periods of the first channel (in [0, 1)).
      std::vector<Dual> lags;
      for (const Dual& t : t_max) {
        const Dual* before = nullptr;
        for (const Dual& r : ref_max)
          if (r.v <= t.v) before = &r;
        if (before && t.v - before->v < ref_period.v) lags.push_back((t - *before) / ref_period);
      }
      if (!lags.empty()) out.push_back({pre + "phase_lag", mean(lags, ns), "1"});
    }
    if (!inc.empty()) out.push_back({pre + nm.phase_inc + "_ms", mean(inc, ns), "ms"});
    if (!dec.empty()) out.push_back({pre + nm.phase_dec + "_ms", mean(dec, ns), "ms"});
    if (!inc.empty() && !dec.empty()) out.push_back({pre + "phase_ratio", mean(inc, ns) / mean(dec, ns), "1"});
    if (!a_min.empty()) out.push_back({pre + "angle_min_deg", mean(a_min, ns), "deg"});
    if (!a_max.empty()) out.push_back({pre + "angle_max_deg", mean(a_max, ns), "deg"});
  }
  for (auto& f : detail::leg_features(model, res, opt, with_grad, roots)) out.push_back(std::move(f));
  derived_features(model, have_global, ns, out);
  return out;
}

}  // namespace

std::vector<Feature> compute_features(const model::OdeModel& model, const solver::SolveResult& result,
                                      const FeatureOptions& options) {
  std::vector<Feature> out;
  for (auto& f : compute(model, result, options, false)) out.push_back({f.name, f.value.v, f.unit});
  return out;
}

std::vector<FeatureGradient> compute_feature_gradients(const model::OdeModel& model,
                                                       const solver::SolveResult& result,
                                                       const FeatureOptions& options) {
  std::vector<FeatureGradient> out;
  for (auto& f : compute(model, result, options, true)) out.push_back({{f.name, f.value.v, f.unit}, f.value.g});
  return out;
}

}  // namespace phasmid::features
