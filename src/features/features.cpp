#include "features/features.hpp"

#include <algorithm>
#include <cmath>

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

struct DualFeature {
  std::string name;
  Dual value;
  std::string unit;
};

std::vector<DualFeature> compute(const model::OdeModel& model, const solver::SolveResult& res,
                                 const FeatureOptions& opt, bool with_grad) {
  const size_t ns = with_grad ? res.sens_params.size() : 0;
  if (with_grad && (ns == 0 || res.s.empty()))
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
  return out;
}

}  // namespace

std::vector<solver::RootSpec> feature_roots(const model::OdeModel& model) {
  std::vector<solver::RootSpec> roots;
  for (const auto& ch : model.angles()) roots.push_back({ch.velocity_state, 0.0, 0});
  return roots;
}

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
