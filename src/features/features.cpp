#include "features/features.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "common/error.hpp"
#include "common/units.hpp"
#include "io/h5_file.hpp"
#include "model/leg_tables.hpp"
#include "features/event_time.hpp"

namespace phasmid::features {
namespace {

// A value with its gradient with respect to the sensitivity parameters (empty gradient: none).
struct Dual {
  double v = 0.0;
  Eigen::VectorXd g;
};
Dual operator+(const Dual& a, const Dual& b) { return {a.v + b.v, a.g + b.g}; }
Dual operator-(const Dual& a, const Dual& b) { return {a.v - b.v, a.g - b.g}; }
Dual operator/(const Dual& a, const Dual& b) { return {a.v / b.v, (a.g * b.v - a.v * b.g) / (b.v * b.v)}; }
Dual scaled(const Dual& a, double c) { return {a.v * c, a.g * c}; }

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

Dual mean(const std::vector<Dual>& xs, size_t ns) {
  Dual m{0.0, Eigen::VectorXd::Zero(ns)};
  for (auto& x : xs) m = m + x;
  return scaled(m, 1.0 / xs.size());
}

// ---- per-leg gait features from ground-contact events (docs/walking_model.md) --------------
// Stance (ground contact) is beta below the threshold of a contact leg the model declares
// (model::ContactLeg; 38 deg, Section 3.2, the criterion that switches the PR sensory pathway).
// Touch-down is beta falling through it, lift-off beta rising through it; both are located by
// root finding. The PR system's retractor CPG neuron (Figs. 3.20-3.22 plot it against beta)
// counts as active above the declared level; below it the PR system is in protraction.
constexpr size_t kNoState = static_cast<size_t>(-1);
struct LegRoot {
  std::string leg;
  size_t beta_state;
  double threshold_deg;
  size_t retractor_state = kNoState;  // if the leg has a PR network
  double retractor_level_mV = 0.0;
};

// Levels from the parameter vector p (empty: the model's own values).
std::vector<LegRoot> leg_roots(const model::OdeModel& model, const std::vector<double>& p = {}) {
  std::vector<LegRoot> out;
  auto value = [&](size_t k) { return p.empty() ? model.parameters().at(k).value : p.at(k); };
  for (const model::ContactLeg& l : model.structure().contact_legs) {
    LegRoot r{l.leg, l.beta_state, value(l.threshold_param)};
    if (l.retractor_state) {
      r.retractor_state = *l.retractor_state;
      r.retractor_level_mV = value(l.retractor_level_param);
    }
    out.push_back(r);
  }
  return out;
}

// Roots of one leg's events after the transient with short episodes removed: an episode (the
// time between two crossings) shorter than `min_ms` is a ripple and goes with its two crossings,
// shortest first, so a ripple merges into the phase it interrupts; of two crossings in the same
// direction the second goes.
std::vector<const solver::Event*> debounced_events(const solver::SolveResult& res, size_t root, double discard_ms,
                                                   double min_ms) {
  std::vector<const solver::Event*> ev;
  for (const auto& e : res.events)
    if (e.root == root && e.t >= discard_ms) ev.push_back(&e);
  for (;;) {
    size_t kmin = ev.size();
    double dmin = min_ms;
    for (size_t k = 0; k + 1 < ev.size(); ++k) {
      if (ev[k]->direction == ev[k + 1]->direction) {
        kmin = k;
        dmin = -1;
        break;
      }
      if (ev[k + 1]->t - ev[k]->t < dmin) {
        dmin = ev[k + 1]->t - ev[k]->t;
        kmin = k;
      }
    }
    if (kmin == ev.size()) break;
    if (dmin < 0) ev.erase(ev.begin() + kmin + 1);
    else ev.erase(ev.begin() + kmin, ev.begin() + kmin + 2);
  }
  return ev;
}

// A located event as a Dual: its time and, with gradients, dt*/dp by the implicit-function
// formula, including the shift of the crossing level when the level itself is a sensitivity
// parameter (dlevel: d level / d p_j in the state's unit): dt*/dp = (dlevel - s) / f.
struct EventDual {
  const solver::Event* e;
  Dual t;
};
EventDual event_dual(const solver::Event& e, const solver::RootSpec& root, size_t ns, bool with_grad,
                     const Eigen::VectorXd& dlevel) {
  EventDual x{&e, {e.t, Eigen::VectorXd::Zero(ns)}};
  if (with_grad && ns) x.t.g = event_time_sensitivity(e, root, ns) + dlevel / e.ydot.at(root.state);
  return x;
}
// The angle (deg) of state i at an event, with its total derivative.
Dual angle_at(const EventDual& x, size_t i, size_t ns, bool with_grad) {
  Dual a{x.e->y.at(i) * units::kDegPerRad, Eigen::VectorXd::Zero(ns)};
  if (with_grad && ns) a.g = state_at_event_sensitivity(*x.e, i, x.t.g) * units::kDegPerRad;
  return a;
}
// d level / d p_j for the sensitivity parameters: `factor` for the model parameter k.
Eigen::VectorXd level_gradient(const solver::SolveResult& res, size_t ns, size_t k, double factor) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(ns);
  for (size_t j = 0; j < ns; ++j)
    if (res.sens_params[j] == k) g[j] = factor;
  return g;
}

// Intervals [begin, end) during which a debounced two-state signal is "on", clipped to
// [t0, t1] (clipped ends carry no gradient); `on_direction` is the crossing that switches it on.
using Intervals = std::vector<std::pair<Dual, Dual>>;
Intervals on_intervals(const std::vector<EventDual>& ev, int on_direction, double t0, double t1, size_t ns) {
  Intervals out;
  if (ev.empty()) return out;
  const Dual start0{t0, Eigen::VectorXd::Zero(ns)}, end1{t1, Eigen::VectorXd::Zero(ns)};
  bool on = ev.front().e->direction != on_direction;  // on before the first event?
  Dual start = start0;
  for (const EventDual& x : ev) {
    if (x.e->direction == on_direction) {
      start = x.t;
      on = true;
    } else if (on) {
      out.push_back({start, x.t});
      on = false;
    }
  }
  if (on) out.push_back({start, end1});
  return out;
}

Dual total(const Intervals& a, size_t ns) {
  Dual s{0.0, Eigen::VectorXd::Zero(ns)};
  for (auto& x : a) s = s + (x.second - x.first);
  return s;
}

Dual overlap(const Intervals& a, const Intervals& b, size_t ns) {
  Dual s{0.0, Eigen::VectorXd::Zero(ns)};
  for (auto& x : a)
    for (auto& y : b) {
      const Dual& hi = x.second.v < y.second.v ? x.second : y.second;
      const Dual& lo = x.first.v > y.first.v ? x.first : y.first;
      if (hi.v > lo.v) s = s + (hi - lo);
    }
  return s;
}

// Ipsilateral leg pairs (a, b) of the phase lags phase_lag.<a>_to_<b>; gait_class reads the
// first, second and fourth.
constexpr const char* kLagPairs[][2] = {{"hind", "middle"}, {"middle", "front"}, {"front", "hind"}, {"hind", "front"}};

double wrap01(double x) { return x - std::floor(x); }

// Circular mean of phases (values in any turn; result in [0, 1)) with its derivative:
// theta = atan2(S, C) / 2 pi, S = sum sin 2 pi phi, C = sum cos 2 pi phi.
Dual circular_mean(const std::vector<Dual>& ph, size_t ns) {
  double c = 0, s = 0;
  Eigen::VectorXd dc = Eigen::VectorXd::Zero(ns), ds = Eigen::VectorXd::Zero(ns);
  for (const Dual& x : ph) {
    const double w = 2 * M_PI * x.v;
    c += std::cos(w);
    s += std::sin(w);
    if (ns) {
      dc -= std::sin(w) * 2 * M_PI * x.g;
      ds += std::cos(w) * 2 * M_PI * x.g;
    }
  }
  Dual m{wrap01(std::atan2(s, c) / (2 * M_PI)), Eigen::VectorXd::Zero(ns)};
  if (ns) m.g = (c * ds - s * dc) / ((c * c + s * s) * 2 * M_PI);
  return m;
}

double circ_dist(double a, double b) {
  double d = std::fabs(wrap01(a - b));
  return std::min(d, 1.0 - d);
}

struct DualFeature {
  std::string name;
  Dual value;
  std::string unit;
};

// `roots`: feature_roots(model), whose state indices the event-time formula reads.
std::vector<DualFeature> leg_features(const model::OdeModel& model, const solver::SolveResult& res,
                                      const FeatureOptions& opt, bool with_grad,
                                      const std::vector<solver::RootSpec>& roots) {
  const size_t ns = with_grad ? res.sens_params.size() : 0;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ns);
  std::vector<DualFeature> out;
  const std::vector<LegRoot> legs = leg_roots(model);
  const size_t first = opt.root_offset + model.angles().size();
  const size_t first_spec = model.angles().size();  // the same roots in feature_roots' own order
  // Roots of the retractor CPGs follow the beta roots, one per leg that has one (feature_roots).
  std::vector<size_t> retractor_root(legs.size(), 0);
  for (size_t l = 0, k = legs.size(); l < legs.size(); ++l)
    if (legs[l].retractor_state != kNoState) retractor_root[l] = k++;
  std::map<std::string, std::vector<Dual>> liftoffs;
  std::map<std::string, Dual> periods;
  auto mean_of = [&](const std::vector<Dual>& v) { return mean(v, ns); };
  for (size_t l = 0; l < legs.size(); ++l) {
    const std::string pre = legs[l].leg + ".";
    // Debounce: a swing or stance episode shorter than min_contact_ms (beta rippling around
    // the threshold while a motoneuron fires) is removed with its two crossings.
    const solver::RootSpec& beta_root = roots[first_spec + l];
    const model::ContactLeg& contact = model.structure().contact_legs[l];
    const Eigen::VectorXd dthr = level_gradient(res, ns, contact.threshold_param, units::kRadPerDeg);
    std::vector<EventDual> ev;
    for (const solver::Event* e : debounced_events(res, first + l, opt.discard_ms, opt.min_contact_ms))
      ev.push_back(event_dual(*e, beta_root, ns, with_grad, dthr));
    std::vector<EventDual> td, lo;  // touch-down (beta falling), lift-off (rising)
    for (const EventDual& x : ev) (x.e->direction < 0 ? td : lo).push_back(x);
    auto next_after = [](const std::vector<EventDual>& v, double t) {
      return std::upper_bound(v.begin(), v.end(), t, [](double a, const EventDual& b) { return a < b.t.v; });
    };
    // Joint excursions during stance (angle at lift-off minus angle at touch-down), deg:
    // thc > 0 retraction during stance (forward stepping), fti < 0 extension during stance.
    for (const auto& ch : model.angles()) {
      if (ch.leg != legs[l].leg || ch.joint == "ctr") continue;
      std::vector<Dual> d;
      for (const EventDual& x : td) {
        auto it = next_after(lo, x.t.v);
        if (it != lo.end()) d.push_back(angle_at(*it, ch.angle_state, ns, with_grad) - angle_at(x, ch.angle_state, ns, with_grad));
      }
      if (!d.empty()) out.push_back({pre + ch.joint + ".stance_change_deg", mean_of(d), "deg"});
    }
    std::vector<Dual> stance, swing;
    for (const EventDual& x : td) {
      auto it = next_after(lo, x.t.v);
      if (it != lo.end()) stance.push_back(it->t - x.t);
    }
    for (const EventDual& x : lo) {
      auto it = next_after(td, x.t.v);
      if (it != td.end()) swing.push_back(it->t - x.t);
    }
    if (lo.size() >= 2) {
      Dual T = scaled(lo.back().t - lo.front().t, 1.0 / (lo.size() - 1));
      out.push_back({pre + "step_period_ms", T, "ms"});
      periods[legs[l].leg] = T;
      for (const EventDual& x : lo) liftoffs[legs[l].leg].push_back(x.t);
    }
    if (!stance.empty()) out.push_back({pre + "stance_ms", mean_of(stance), "ms"});
    if (!swing.empty()) out.push_back({pre + "swing_ms", mean_of(swing), "ms"});
    if (!stance.empty() && !swing.empty())
      out.push_back({pre + "duty_factor", mean_of(stance) / (mean_of(stance) + mean_of(swing)), "1"});
    // Figs. 3.20 / 3.22: does the PR system's protraction (retractor CPG inactive) fall into the
    // swing, and its retraction into the stance? Over the whole analysed window, both as
    // fractions: of the protraction time spent in ground contact, of the stance time with the
    // retractor CPG active.
    if (legs[l].retractor_state != kNoState && !ev.empty()) {
      const double t0 = opt.discard_ms, t1 = res.t.empty() ? t0 : res.t.back();
      const solver::RootSpec& cpg_root = roots[first_spec + retractor_root[l]];
      const Eigen::VectorXd dvh = level_gradient(res, ns, contact.retractor_level_param, 1.0);
      std::vector<EventDual> cpg;
      for (const solver::Event* e : debounced_events(res, opt.root_offset + first_spec + retractor_root[l],
                                                     opt.discard_ms, opt.min_contact_ms))
        cpg.push_back(event_dual(*e, cpg_root, ns, with_grad, dvh));
      const Intervals stance_iv = on_intervals(ev, -1, t0, t1, ns);  // beta falling: touch-down
      const Intervals retract = on_intervals(cpg, +1, t0, t1, ns);   // V rising: retractor on
      const Intervals protract = on_intervals(cpg, -1, t0, t1, ns);
      const Dual prot = total(protract, ns), st = total(stance_iv, ns);
      if (cpg.size() >= 2 && prot.v > 0 && st.v > 0) {
        out.push_back({pre + "protraction_in_stance_fraction", overlap(protract, stance_iv, ns) / prot, "1"});
        out.push_back({pre + "stance_retraction_fraction", overlap(retract, stance_iv, ns) / st, "1"});
      }
    }
  }
  // Phase lag of leg b after leg a: (lift-off of b - preceding lift-off of a) / period of a,
  // circular mean over the cycles after the transient, in [0, 1).
  auto lag = [&](const std::string& a, const std::string& b, Dual& value) {
    if (!liftoffs.count(a) || !liftoffs.count(b)) return false;
    const auto& la = liftoffs[a];
    std::vector<Dual> ph;
    for (const Dual& t : liftoffs[b]) {
      auto it = std::upper_bound(la.begin(), la.end(), t.v, [](double x, const Dual& y) { return x < y.v; });
      if (it == la.begin()) continue;
      Dual p = (t - *(it - 1)) / periods[a];
      p.v = wrap01(p.v);  // whole turns do not change the phase or its derivative
      ph.push_back(p);
    }
    if (ph.empty()) return false;
    value = circular_mean(ph, ns);
    return true;
  };
  std::map<std::string, double> lags;
  for (auto& pr : kLagPairs) {
    Dual v{0.0, zero};
    if (lag(pr[0], pr[1], v)) {
      lags[std::string(pr[0]) + "_to_" + pr[1]] = v.v;
      out.push_back({std::string("phase_lag.") + pr[0] + "_to_" + pr[1], v, "1"});
    }
  }
  if (lags.count("hind_to_middle") && lags.count("middle_to_front") && lags.count("hind_to_front")) {
    // A class, piecewise constant in the parameters: zero gradient.
    out.push_back({"gait_class",
                   {static_cast<double>(classify_gait(lags["hind_to_middle"], lags["middle_to_front"], lags["hind_to_front"])), zero},
                   "1"});
  }
  return out;
}

bool has_three_contact_legs(const model::OdeModel& model) {
  return model.contact_leg("hind") && model.contact_leg("middle") && model.contact_leg("front");
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
  if (!has_three_contact_legs(model)) return;
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
  for (auto& f : leg_features(model, res, opt, with_grad, roots)) out.push_back(std::move(f));
  derived_features(model, have_global, ns, out);
  return out;
}

void channel_catalogue(const model::OdeModel& model, std::vector<FeatureInfo>& out) {
  if (model.angles().empty()) return;
  const auto& first = model.angles().front();
  out.push_back({"period_ms", "ms", true, "cycle period of the first angle channel (" + first.leg + "." + first.joint + ")"});
  for (size_t c = 0; c < model.angles().size(); ++c) {
    const auto& ch = model.angles()[c];
    const std::string pre = ch.leg + "." + ch.joint + ".";
    const model::JointNaming nm = model::joint_naming(model::parse_joint(ch.joint));
    const std::string inc = nm.phase_inc, dec = nm.phase_dec;
    out.push_back({pre + "period_ms", "ms", true, "mean time between the angle's maxima"});
    out.push_back({pre + inc + "_fraction", "1", true, "mean " + inc + " time / period"});
    if (c > 0)
      out.push_back({pre + "phase_lag", "1", true, "mean lag of the angle's maxima after the first channel's, in its periods"});
    out.push_back({pre + inc + "_ms", "ms", true, "mean duration of " + inc + " (angle rising, minimum to maximum)"});
    out.push_back({pre + dec + "_ms", "ms", true, "mean duration of " + dec + " (angle falling, maximum to minimum)"});
    out.push_back({pre + "phase_ratio", "1", true, inc + " time / " + dec + " time"});
    out.push_back({pre + "angle_min_deg", "deg", true, "mean angle at the turning-point minima"});
    out.push_back({pre + "angle_max_deg", "deg", true, "mean angle at the turning-point maxima"});
  }
}

void leg_catalogue(const model::OdeModel& model, std::vector<FeatureInfo>& out) {
  for (const model::ContactLeg& l : model.structure().contact_legs) {
    const std::string pre = l.leg + ".";
    for (const auto& ch : model.angles())
      if (ch.leg == l.leg && ch.joint != "ctr")
        out.push_back({pre + ch.joint + ".stance_change_deg", "deg", true,
                       "mean change of the " + ch.joint + " angle from touch-down to lift-off"});
    out.push_back({pre + "step_period_ms", "ms", true, "mean time between lift-offs"});
    out.push_back({pre + "stance_ms", "ms", true, "mean stance duration (touch-down to lift-off)"});
    out.push_back({pre + "swing_ms", "ms", true, "mean swing duration (lift-off to touch-down)"});
    out.push_back({pre + "duty_factor", "1", true, "stance / (stance + swing)"});
    if (l.retractor_state) {
      out.push_back({pre + "protraction_in_stance_fraction", "1", true,
                     "fraction of the PR protraction (retractor CPG inactive) spent in stance"});
      out.push_back({pre + "stance_retraction_fraction", "1", true, "fraction of the stance with the retractor CPG active"});
    }
  }
  auto has = [&](const char* leg) { return model.contact_leg(leg) != nullptr; };
  for (auto& pr : kLagPairs)
    if (has(pr[0]) && has(pr[1]))
      out.push_back({std::string("phase_lag.") + pr[0] + "_to_" + pr[1], "1", true,
                     std::string("circular mean lag of the ") + pr[1] + " leg's lift-offs after the " + pr[0] +
                         " leg's, in its step periods"});
  if (has("hind") && has("middle") && has("front"))
    out.push_back({"gait_class", "1", false, "2 tripod, 1 tetrapod, 0 irregular, from the three phase lags (a class: no gradient)"});
}

}  // namespace

std::vector<FeatureInfo> feature_catalogue(const model::OdeModel& model) {
  std::vector<FeatureInfo> out;
  channel_catalogue(model, out);
  leg_catalogue(model, out);
  if (model.angles().empty()) return out;
  out.push_back({"oscillates", "1", false, "1 when the first angle channel has a period over the window (the rhythm exists), else 0"});
  if (has_three_contact_legs(model)) {
    out.push_back({"is_tripod", "1", false, "1 when gait_class is 2 (tripod), else 0 (also where the gait is undefined)"});
    out.push_back({"is_tetrapod", "1", false, "1 when gait_class is 1 (tetrapod), else 0 (also where the gait is undefined)"});
  }
  return out;
}

std::vector<solver::RootSpec> feature_roots(const model::OdeModel& model) { return feature_roots(model, {}); }

std::vector<solver::RootSpec> feature_roots(const model::OdeModel& model, const std::vector<double>& p) {
  std::vector<solver::RootSpec> roots;
  for (const auto& ch : model.angles()) roots.push_back({ch.velocity_state, 0.0, 0});
  const std::vector<LegRoot> legs = leg_roots(model, p);
  for (const auto& l : legs) roots.push_back({l.beta_state, units::deg_to_rad(l.threshold_deg), 0});
  for (const auto& l : legs)
    if (l.retractor_state != kNoState) roots.push_back({l.retractor_state, l.retractor_level_mV, 0});
  return roots;
}

int classify_gait(double hind_to_middle, double middle_to_front, double hind_to_front, double tolerance) {
  // Tripod (Fig. 2.19): front and hind in phase, middle in antiphase to both.
  if (circ_dist(hind_to_front, 0.0) < tolerance && circ_dist(hind_to_middle, 0.5) < tolerance &&
      circ_dist(middle_to_front, 0.5) < tolerance)
    return 2;
  // Tetrapod (Fig. 2.17): metachronal wave hind -> middle -> front, lags 1/3 each.
  if (circ_dist(hind_to_middle, 1.0 / 3) < tolerance && circ_dist(middle_to_front, 1.0 / 3) < tolerance &&
      circ_dist(hind_to_front, 2.0 / 3) < tolerance)
    return 1;
  return 0;
}

const char* gait_class_name(int c) { return c == 2 ? "tripod" : c == 1 ? "tetrapod" : "irregular"; }

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

void write_features_h5(io::H5Writer& out, const std::vector<Feature>& features) {
  out.ensure_group("/features");
  for (const auto& f : features) out.write_scalar("/features/" + f.name, f.value, f.unit);
}

std::vector<Feature> read_features_h5(const io::H5Reader& in) {
  if (!in.is_group("/features")) throw Error(in.path() + ": no /features group (not a phasmid run file?)");
  std::vector<Feature> out;
  for (const auto& name : in.children("/features")) {
    const std::string path = "/features/" + name;
    if (in.is_group(path)) continue;
    auto d = in.dims(path);
    if (!d.empty() && !(d.size() == 1 && d[0] == 1)) continue;  // scalars only
    std::vector<double> v = in.read_doubles(path);
    if (v.size() != 1) continue;
    std::string unit = "1";
    try {
      unit = in.read_string_attribute(path, "units");
    } catch (const Error&) {
    }
    out.push_back({name, v[0], unit});
  }
  return out;
}

}  // namespace phasmid::features
