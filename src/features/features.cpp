#include "features/features.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "common/error.hpp"
#include "io/h5_file.hpp"
#include "model/leg_tables.hpp"
#include "sensitivity/event_time.hpp"

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

constexpr double kDeg = 180.0 / M_PI;

// Extrema of one channel in time order, after the transient, with wiggles removed.
std::vector<Extremum> channel_extrema(const model::AngleChannel& ch, size_t root_index, const solver::RootSpec& root,
                                      const solver::SolveResult& res, const FeatureOptions& opt, bool with_grad) {
  const size_t ns = with_grad ? res.sens_params.size() : 0;
  std::vector<Extremum> ex;
  for (const auto& e : res.events) {
    if (e.root != root_index || e.t < opt.discard_ms) continue;
    Extremum x;
    x.is_max = e.direction < 0;  // velocity falls through zero at a maximum
    x.t.v = e.t;
    x.angle.v = e.y.at(ch.angle_state) * kDeg;
    x.t.g = Eigen::VectorXd::Zero(ns);
    x.angle.g = Eigen::VectorXd::Zero(ns);
    if (with_grad) {
      x.t.g = sensitivity::event_time_sensitivity(e, root, ns);
      x.angle.g = sensitivity::state_at_event_sensitivity(e, ch.angle_state, x.t.g) * kDeg;
    }
    ex.push_back(std::move(x));
  }
  // Keep the turning points of the gait cycle only (peak detection with hysteresis, as in
  // Billauer's peakdet): a maximum counts once the angle has fallen more than `delta` below
  // it, a minimum once it has risen more than `delta` above it. Damped oscillations around
  // an equilibrium within one phase are thereby skipped, and an extremum the run ends on
  // before it is confirmed is dropped.
  if (ex.empty()) return ex;
  double lo = ex[0].angle.v, hi = lo;
  for (auto& x : ex) {
    lo = std::min(lo, x.angle.v);
    hi = std::max(hi, x.angle.v);
  }
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
  return kept;
}

Dual mean(const std::vector<Dual>& xs, size_t ns) {
  Dual m{0.0, Eigen::VectorXd::Zero(ns)};
  for (auto& x : xs) m = m + x;
  return scaled(m, 1.0 / xs.size());
}

// ---- per-leg gait features from ground-contact events (docs/walking_model.md) --------------
// Stance (ground contact) is beta below the leg's PR threshold `<leg>.coupling.beta_thr_pr`
// (38 deg, Section 3.2): the same criterion that switches the PR sensory pathway. Touch-down is
// beta falling through it, lift-off beta rising through it; both are located by root finding.
struct LegRoot {
  std::string leg;
  size_t beta_state;
  double threshold_deg;
};

std::vector<LegRoot> leg_roots(const model::OdeModel& model) {
  std::vector<LegRoot> out;
  for (const auto& ch : model.angles()) {
    if (ch.joint != "ctr") continue;
    const std::string thr = ch.leg + ".coupling.beta_thr_pr";
    if (!model.parameters().contains(thr)) continue;
    out.push_back({ch.leg, ch.angle_state, model.parameters().value(thr)});
  }
  return out;
}

double wrap01(double x) { return x - std::floor(x); }

// Circular mean of phases in [0, 1).
double circular_mean(const std::vector<double>& ph) {
  double c = 0, s = 0;
  for (double x : ph) {
    c += std::cos(2 * M_PI * x);
    s += std::sin(2 * M_PI * x);
  }
  return wrap01(std::atan2(s, c) / (2 * M_PI));
}

double circ_dist(double a, double b) {
  double d = std::fabs(wrap01(a - b));
  return std::min(d, 1.0 - d);
}

std::vector<Feature> leg_features(const model::OdeModel& model, const solver::SolveResult& res,
                                  const FeatureOptions& opt) {
  std::vector<Feature> out;
  const std::vector<LegRoot> legs = leg_roots(model);
  const size_t first = opt.root_offset + model.angles().size();
  std::map<std::string, std::vector<double>> liftoffs;
  std::map<std::string, double> periods;
  for (size_t l = 0; l < legs.size(); ++l) {
    std::vector<double> td, lo;  // touch-down, lift-off times
    std::map<double, const solver::Event*> at;
    // Debounce: a swing or stance episode shorter than min_contact_ms (beta rippling around
    // the threshold while a motoneuron fires) is removed with its two crossings.
    std::vector<const solver::Event*> ev;
    for (const auto& e : res.events)
      if (e.root == first + l && e.t >= opt.discard_ms) ev.push_back(&e);
    // The shortest episode goes first, so a ripple merges into the phase it interrupts.
    for (;;) {
      size_t kmin = ev.size();
      double dmin = opt.min_contact_ms;
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
    for (const solver::Event* e : ev) {
      (e->direction < 0 ? td : lo).push_back(e->t);
      at[e->t] = e;
    }
    // Joint excursions during stance (angle at lift-off minus angle at touch-down), deg:
    // thc > 0 retraction during stance (forward stepping), fti < 0 extension during stance.
    for (const auto& ch : model.angles()) {
      if (ch.leg != legs[l].leg || ch.joint == "ctr") continue;
      std::vector<double> d;
      for (double t : td) {
        auto it = std::upper_bound(lo.begin(), lo.end(), t);
        if (it != lo.end()) d.push_back((at[*it]->y[ch.angle_state] - at[t]->y[ch.angle_state]) * kDeg);
      }
      if (!d.empty()) {
        double a = 0;
        for (double x : d) a += x;
        out.push_back({legs[l].leg + "." + ch.joint + ".stance_change_deg", a / d.size(), "deg"});
      }
    }
    const std::string pre = legs[l].leg + ".";
    std::vector<double> stance, swing;
    for (double t : td) {
      auto it = std::upper_bound(lo.begin(), lo.end(), t);
      if (it != lo.end()) stance.push_back(*it - t);
    }
    for (double t : lo) {
      auto it = std::upper_bound(td.begin(), td.end(), t);
      if (it != td.end()) swing.push_back(*it - t);
    }
    auto avg = [](const std::vector<double>& v) {
      double a = 0;
      for (double x : v) a += x;
      return a / v.size();
    };
    if (lo.size() >= 2) {
      double T = (lo.back() - lo.front()) / (lo.size() - 1);
      out.push_back({pre + "step_period_ms", T, "ms"});
      periods[legs[l].leg] = T;
      liftoffs[legs[l].leg] = lo;
    }
    if (!stance.empty()) out.push_back({pre + "stance_ms", avg(stance), "ms"});
    if (!swing.empty()) out.push_back({pre + "swing_ms", avg(swing), "ms"});
    if (!stance.empty() && !swing.empty())
      out.push_back({pre + "duty_factor", avg(stance) / (avg(stance) + avg(swing)), "1"});
  }
  // Phase lag of leg b after leg a: (lift-off of b - preceding lift-off of a) / period of a,
  // circular mean over the cycles after the transient, in [0, 1).
  auto lag = [&](const std::string& a, const std::string& b, double& value) {
    if (!liftoffs.count(a) || !liftoffs.count(b)) return false;
    const auto& la = liftoffs[a];
    std::vector<double> ph;
    for (double t : liftoffs[b]) {
      auto it = std::upper_bound(la.begin(), la.end(), t);
      if (it == la.begin()) continue;
      ph.push_back(wrap01((t - *(it - 1)) / periods[a]));
    }
    if (ph.empty()) return false;
    value = circular_mean(ph);
    return true;
  };
  const char* pairs[][2] = {{"hind", "middle"}, {"middle", "front"}, {"front", "hind"}, {"hind", "front"}};
  std::map<std::string, double> lags;
  for (auto& pr : pairs) {
    double v;
    if (lag(pr[0], pr[1], v)) {
      lags[std::string(pr[0]) + "_to_" + pr[1]] = v;
      out.push_back({std::string("phase_lag.") + pr[0] + "_to_" + pr[1], v, "1"});
    }
  }
  if (lags.count("hind_to_middle") && lags.count("middle_to_front") && lags.count("hind_to_front")) {
    out.push_back({"gait_class", static_cast<double>(classify_gait(lags["hind_to_middle"], lags["middle_to_front"],
                                                                   lags["hind_to_front"])),
                   "1"});
  }
  return out;
}

struct DualFeature {
  std::string name;
  Dual value;
  std::string unit;
};

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
  if (!with_grad) {
    for (auto& f : leg_features(model, res, opt)) out.push_back({f.name, {f.value, {}}, f.unit});
  }
  return out;
}

}  // namespace

std::vector<solver::RootSpec> feature_roots(const model::OdeModel& model) {
  std::vector<solver::RootSpec> roots;
  for (const auto& ch : model.angles()) roots.push_back({ch.velocity_state, 0.0, 0});
  for (const auto& l : leg_roots(model)) roots.push_back({l.beta_state, l.threshold_deg * M_PI / 180.0, 0});
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
