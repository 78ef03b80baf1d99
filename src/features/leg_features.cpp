// Per-leg gait features from ground-contact events, the phase lags between legs, and the gait
// class they give (docs/walking_model.md).
#include <algorithm>
#include <cmath>
#include <map>

#include "common/units.hpp"
#include "features/event_time.hpp"
#include "features/feature_parts.hpp"

namespace phasmid::features {
namespace detail {
namespace {

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

// One run's leg features in the making: what each leg's steps read, and what the phase lags
// collect from the legs.
struct LegRun {
  const model::OdeModel& model;
  const solver::SolveResult& res;
  const FeatureOptions& opt;
  bool with_grad;
  const std::vector<solver::RootSpec>& roots;
  size_t ns;
  std::vector<LegRoot> legs;
  size_t first;       // the first beta root, as numbered in res.events
  size_t first_spec;  // the same root in feature_roots' own order
  // Roots of the retractor CPGs follow the beta roots, one per leg that has one (feature_roots):
  // per leg, its root's offset from first_spec.
  std::vector<size_t> retractor_root;
  std::map<std::string, std::vector<Dual>> liftoffs;  // per leg with a step period
  std::map<std::string, Dual> periods;
  std::vector<DualFeature> out;
};

// A leg's contact events after the transient, debounced: a swing or stance episode shorter than
// min_contact_ms (beta rippling around the threshold while a motoneuron fires) is removed with
// its two crossings.
struct ContactEvents {
  std::vector<EventDual> all;
  std::vector<EventDual> td;  // touch-down (beta falling)
  std::vector<EventDual> lo;  // lift-off (rising)
};
ContactEvents contact_events(const LegRun& run, size_t l) {
  const solver::RootSpec& beta_root = run.roots[run.first_spec + l];
  const model::ContactLeg& contact = run.model.structure().contact_legs[l];
  const Eigen::VectorXd dthr = level_gradient(run.res, run.ns, contact.threshold_param, units::kRadPerDeg);
  ContactEvents c;
  for (const solver::Event* e : debounced_events(run.res, run.first + l, run.opt.discard_ms, run.opt.min_contact_ms))
    c.all.push_back(event_dual(*e, beta_root, run.ns, run.with_grad, dthr));
  for (const EventDual& x : c.all) (x.e->direction < 0 ? c.td : c.lo).push_back(x);
  return c;
}

// The first event of v after time t.
std::vector<EventDual>::const_iterator next_after(const std::vector<EventDual>& v, double t) {
  return std::upper_bound(v.begin(), v.end(), t, [](double a, const EventDual& b) { return a < b.t.v; });
}

// Joint excursions during stance (angle at lift-off minus angle at touch-down), deg:
// thc > 0 retraction during stance (forward stepping), fti < 0 extension during stance.
void stance_changes(LegRun& run, size_t l, const ContactEvents& c) {
  const std::string pre = run.legs[l].leg + ".";
  for (const auto& ch : run.model.angles()) {
    if (ch.leg != run.legs[l].leg || ch.joint == "ctr") continue;
    std::vector<Dual> d;
    for (const EventDual& x : c.td) {
      auto it = next_after(c.lo, x.t.v);
      if (it != c.lo.end())
        d.push_back(angle_at(*it, ch.angle_state, run.ns, run.with_grad) -
                    angle_at(x, ch.angle_state, run.ns, run.with_grad));
    }
    if (!d.empty()) run.out.push_back({pre + ch.joint + ".stance_change_deg", mean(d, run.ns), "deg"});
  }
}

// Step period, stance, swing and duty factor of a leg; its lift-offs and period are kept for the
// phase lags.
void step_timing(LegRun& run, size_t l, const ContactEvents& c) {
  const std::string& leg = run.legs[l].leg;
  const std::string pre = leg + ".";
  std::vector<Dual> stance, swing;
  for (const EventDual& x : c.td) {
    auto it = next_after(c.lo, x.t.v);
    if (it != c.lo.end()) stance.push_back(it->t - x.t);
  }
  for (const EventDual& x : c.lo) {
    auto it = next_after(c.td, x.t.v);
    if (it != c.td.end()) swing.push_back(it->t - x.t);
  }
  if (c.lo.size() >= 2) {
    Dual T = scaled(c.lo.back().t - c.lo.front().t, 1.0 / (c.lo.size() - 1));
    run.out.push_back({pre + "step_period_ms", T, "ms"});
    run.periods[leg] = T;
    for (const EventDual& x : c.lo) run.liftoffs[leg].push_back(x.t);
  }
  const size_t ns = run.ns;
  if (!stance.empty()) run.out.push_back({pre + "stance_ms", mean(stance, ns), "ms"});
  if (!swing.empty()) run.out.push_back({pre + "swing_ms", mean(swing, ns), "ms"});
  if (!stance.empty() && !swing.empty())
    run.out.push_back({pre + "duty_factor", mean(stance, ns) / (mean(stance, ns) + mean(swing, ns)), "1"});
}

// Figs. 3.20 / 3.22: does the PR system's protraction (retractor CPG inactive) fall into the
// swing, and its retraction into the stance? Over the whole analysed window, both as
// fractions: of the protraction time spent in ground contact, of the stance time with the
// retractor CPG active.
void protraction_fractions(LegRun& run, size_t l, const ContactEvents& c) {
  if (run.legs[l].retractor_state == kNoState || c.all.empty()) return;
  const size_t ns = run.ns;
  const std::string pre = run.legs[l].leg + ".";
  const double t0 = run.opt.discard_ms, t1 = run.res.t.empty() ? t0 : run.res.t.back();
  const solver::RootSpec& cpg_root = run.roots[run.first_spec + run.retractor_root[l]];
  const model::ContactLeg& contact = run.model.structure().contact_legs[l];
  const Eigen::VectorXd dvh = level_gradient(run.res, ns, contact.retractor_level_param, 1.0);
  std::vector<EventDual> cpg;
  for (const solver::Event* e : debounced_events(run.res, run.opt.root_offset + run.first_spec + run.retractor_root[l],
                                                 run.opt.discard_ms, run.opt.min_contact_ms))
    cpg.push_back(event_dual(*e, cpg_root, ns, run.with_grad, dvh));
  const Intervals stance_iv = on_intervals(c.all, -1, t0, t1, ns);  // beta falling: touch-down
  const Intervals retract = on_intervals(cpg, +1, t0, t1, ns);      // V rising: retractor on
  const Intervals protract = on_intervals(cpg, -1, t0, t1, ns);
  const Dual prot = total(protract, ns), st = total(stance_iv, ns);
  if (cpg.size() >= 2 && prot.v > 0 && st.v > 0) {
    run.out.push_back({pre + "protraction_in_stance_fraction", overlap(protract, stance_iv, ns) / prot, "1"});
    run.out.push_back({pre + "stance_retraction_fraction", overlap(retract, stance_iv, ns) / st, "1"});
  }
}

// Phase lag of leg b after leg a: (lift-off of b - preceding lift-off of a) / period of a,
// circular mean over the cycles after the transient, in [0, 1). False if either leg has no
// step period or no lift-off of b follows one of a.
bool phase_lag(const LegRun& run, const std::string& a, const std::string& b, Dual& value) {
  if (!run.liftoffs.count(a) || !run.liftoffs.count(b)) return false;
  const auto& la = run.liftoffs.at(a);
  std::vector<Dual> ph;
  for (const Dual& t : run.liftoffs.at(b)) {
    auto it = std::upper_bound(la.begin(), la.end(), t.v, [](double x, const Dual& y) { return x < y.v; });
    if (it == la.begin()) continue;
    Dual p = (t - *(it - 1)) / run.periods.at(a);
    p.v = wrap01(p.v);  // whole turns do not change the phase or its derivative
    ph.push_back(p);
  }
  if (ph.empty()) return false;
  value = circular_mean(ph, run.ns);
  return true;
}

// phase_lag.<a>_to_<b> for the pairs of kLagPairs, and gait_class from three of them.
void lag_features(LegRun& run) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(run.ns);
  std::map<std::string, double> lags;
  for (auto& pr : kLagPairs) {
    Dual v{0.0, zero};
    if (phase_lag(run, pr[0], pr[1], v)) {
      lags[std::string(pr[0]) + "_to_" + pr[1]] = v.v;
      run.out.push_back({std::string("phase_lag.") + pr[0] + "_to_" + pr[1], v, "1"});
    }
  }
  if (lags.count("hind_to_middle") && lags.count("middle_to_front") && lags.count("hind_to_front")) {
    // A class, piecewise constant in the parameters: zero gradient.
    run.out.push_back(
        {"gait_class",
         {static_cast<double>(classify_gait(lags["hind_to_middle"], lags["middle_to_front"], lags["hind_to_front"])), zero},
         "1"});
  }
}

double circ_dist(double a, double b) {
  double d = std::fabs(wrap01(a - b));
  return std::min(d, 1.0 - d);
}

}  // namespace

std::vector<DualFeature> leg_features(const model::OdeModel& model, const solver::SolveResult& res,
                                      const FeatureOptions& opt, bool with_grad,
                                      const std::vector<solver::RootSpec>& roots) {
  const size_t ns = with_grad ? res.sens_params.size() : 0;
  LegRun run{model, res, opt, with_grad, roots, ns, leg_roots(model), opt.root_offset + model.angles().size(),
             model.angles().size(), {}, {}, {}, {}};
  run.retractor_root.assign(run.legs.size(), 0);
  for (size_t l = 0, k = run.legs.size(); l < run.legs.size(); ++l)
    if (run.legs[l].retractor_state != kNoState) run.retractor_root[l] = k++;
  for (size_t l = 0; l < run.legs.size(); ++l) {
    const ContactEvents c = contact_events(run, l);
    stance_changes(run, l, c);
    step_timing(run, l, c);
    protraction_fractions(run, l, c);
  }
  lag_features(run);
  return run.out;
}

ContactTimes contact_times(const model::OdeModel& model, const solver::SolveResult& res, const FeatureOptions& opt,
                           bool with_grad, const std::vector<solver::RootSpec>& roots, const std::string& leg) {
  const size_t ns = with_grad ? res.sens_params.size() : 0;
  LegRun run{model, res, opt, with_grad, roots, ns, leg_roots(model), opt.root_offset + model.angles().size(),
             model.angles().size(), {}, {}, {}, {}};
  ContactTimes out;
  for (size_t l = 0; l < run.legs.size(); ++l) {
    if (run.legs[l].leg != leg) continue;
    const ContactEvents c = contact_events(run, l);
    for (const EventDual& x : c.td) out.touchdown.push_back(x.t);
    for (const EventDual& x : c.lo) out.liftoff.push_back(x.t);
  }
  return out;
}

bool has_three_contact_legs(const model::OdeModel& model) {
  return model.contact_leg("hind") && model.contact_leg("middle") && model.contact_leg("front");
}

}  // namespace detail

int classify_gait(double hind_to_middle, double middle_to_front, double hind_to_front, double tolerance) {
  using detail::circ_dist;
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

}  // namespace phasmid::features
