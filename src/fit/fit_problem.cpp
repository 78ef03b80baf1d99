#include "fit/fit_problem.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "common/error.hpp"
#include "common/format.hpp"
#include "common/units.hpp"
#include "features/joint_range.hpp"
#include "io/h5_file.hpp"
#include "io/trajectory_writer.hpp"

namespace phasmid::fit {
namespace {
// deg/s per unit of a velocity state.
double deg_per_s(const std::string& unit, const std::string& state) {
  if (unit == "rad/s") return units::kDegPerRad;
  if (unit == "rad/ms") return units::kDegPerRad * 1000.0;
  if (unit == "deg/s") return 1.0;
  throw Error("internal: velocity state '" + state + "' has unit '" + unit + "' (expected rad/s or rad/ms)");
}

std::string channel_name(const model::AngleChannel& a) { return a.leg + "." + a.joint; }

size_t find_channel(const model::OdeModel& m, const std::string& name, const std::string& origin) {
  for (size_t c = 0; c < m.angles().size(); ++c)
    if (channel_name(m.angles()[c]) == name) return c;
  std::string have;
  for (auto& a : m.angles()) have += (have.empty() ? "" : ", ") + channel_name(a);
  throw Error((origin.empty() ? "" : origin + ": ") + "the model has no angle '" + name + "' (it has: " + have + ")");
}

// The features a fit may target, from the model's feature catalogue: those with event-time
// gradients, and those without (classes) for derivative-free optimisers only.
void target_features(const model::OdeModel& m, std::set<std::string>& with_gradient, std::set<std::string>& values_only) {
  for (const features::FeatureInfo& f : features::feature_catalogue(m))
    (f.differentiable ? with_gradient : values_only).insert(f.name);
}

std::vector<size_t> match_parameters(const model::ParameterSet& ps, const std::string& id, const std::string& w) {
  if (!is_parameter_pattern(id)) {
    try {
      return {ps.index(id)};
    } catch (const Error& e) {
      throw Error(w + e.what());
    }
  }
  std::vector<size_t> ks;
  for (size_t k = 0; k < ps.size(); ++k)
    if (parameter_id_matches(id, ps.at(k).name)) ks.push_back(k);
  if (ks.empty()) throw Error(w + "no model parameter matches '" + id + "'; `phasmid params CONFIG` lists them");
  return ks;
}

}  // namespace

struct FitProblem::Run {
  solver::SolveResult res;
  std::vector<double> p;
  std::vector<double> out_times;
  std::vector<size_t> switch_out;
  std::vector<std::vector<size_t>> kin_out;  // per target, per data sample: output index
  std::vector<double> offsets;
  size_t index_of(double t) const {
    return static_cast<size_t>(std::lower_bound(out_times.begin(), out_times.end(), t) - out_times.begin());
  }
};

FitProblem::FitProblem(const model::OdeModel& model, std::vector<FitParameter> parameters, Targets targets,
                       ProblemSettings settings)
    : model_(model), targets_(std::move(targets)), settings_(settings) {
  params_ = std::move(parameters);
  if (targets_.empty()) throw Error("the fit has no targets (give [[fit.feature]], [[fit.switch]] or data)");
  const auto& ps = model_.parameters();
  base_p_ = ps.values();
  std::set<std::string> offset_ids;
  std::map<std::string, std::string> roles;  // id -> what it is (an offset and a noise share "deg")
  auto add_offset = [&](const std::string& id, const std::string& unit, const std::string& origin, const char* what) {
    if (id.empty()) return;
    if (ps.contains(id)) throw Error(origin + ": " + what + " parameter '" + id + "' is also a model parameter");
    auto [it, fresh] = offset_units_.emplace(id, unit);
    if (!fresh && it->second != unit) throw Error(origin + ": parameter '" + id + "' has two roles (" + it->second + " and " + unit + ")");
    auto [role, new_role] = roles.emplace(id, what);
    if (!new_role && role->second != what)
      throw Error(origin + ": parameter '" + id + "' has two roles (" + role->second + " and " + what + ")");
    offset_ids.insert(id);
  };
  for (auto& k : targets_.kinematics) add_offset(k.time_offset_parameter, "ms", k.origin, "time offset");
  for (auto& t : targets_.step_cycles)
    for (auto& o : t.observables) {
      add_offset(o.offset_parameter, "deg", o.origin, "offset");
      add_offset(o.scale_parameter, "1", o.origin, "scale");
      add_offset(o.sigma_parameter, "deg", o.origin, "noise");
      if (!o.sigma_parameter.empty()) noise_ids_.insert(o.sigma_parameter);
    }
  check_parameters(offset_ids);
  map_estimates(offset_ids);
  if (est_.empty()) throw Error("no parameter is estimated (set estimate = 1 for at least one)");

  // Parameters that move switch times or set the initial state are exact too: the solver
  // applies the jump conditions and s(0) = dy0/dp (docs/sensitivity.md).
  label_targets();
}

// Each parameter given once, inside its model parameter's admissible range, naming model
// parameters no other id names; fixed ones set in base_p_.
void FitProblem::check_parameters(const std::set<std::string>& offset_ids) {
  const auto& ps = model_.parameters();
  std::set<std::string> seen;
  std::map<size_t, std::string> claimed;  // model parameter -> the id that names it
  for (auto& fp : params_) {
    const std::string w = fp.origin.empty() ? "" : fp.origin + ": ";
    if (!seen.insert(fp.id).second) throw Error(w + "parameter '" + fp.id + "' given twice");
    validate(fp);
    if (noise_ids_.count(fp.id)) {
      if (!((fp.estimate ? fp.lower : fp.nominal) > 0))
        throw Error(w + "'" + fp.id + "' (an observable's noise, deg) needs " + (fp.estimate ? "a lower bound" : "a value") + " > 0");
      continue;
    }
    if (offset_ids.count(fp.id)) {
      if (fp.scale != Scale::Lin) throw Error(w + "'" + fp.id + "' (an offset or observable scale) must use parameterScale lin");
      continue;
    }
    std::vector<size_t> ks = match_parameters(ps, fp.id, w);
    for (size_t k : ks) {
      const model::Parameter& mp = ps.at(k);
      // Two ids naming one model parameter would estimate it twice (or fix and estimate it).
      auto [it, fresh] = claimed.emplace(k, fp.id);
      if (!fresh)
        throw Error(w + "parameter '" + fp.id + "' names " + mp.name + ", which '" + it->second + "' names already");
      if (fp.estimate) {
        if (fp.lower < mp.lower || fp.upper > mp.upper)
          throw Error(w + "bounds [" + format_g(fp.lower) + ", " + format_g(fp.upper) + "] of '" + mp.name +
                      "' leave the admissible range [" + format_g(mp.lower) + ", " + format_g(mp.upper) + "] " + mp.unit);
      } else {
        if (fp.nominal < mp.lower || fp.nominal > mp.upper)
          throw Error(w + "fixed value " + format_g(fp.nominal) + " of '" + mp.name + "' outside the admissible range");
        base_p_[k] = fp.nominal;
      }
    }
  }
}

// Per estimated parameter: the model parameters it sets and their sensitivity columns, or a
// kinematic target's time offset.
void FitProblem::map_estimates(const std::set<std::string>& offset_ids) {
  const auto& ps = model_.parameters();
  for (auto& fp : params_) {
    if (!fp.estimate) continue;
    EstMap e{false, {}, {}, offset_ids.count(fp.id) ? offset_units_.at(fp.id) : ""};
    if (!offset_ids.count(fp.id)) {
      e.is_model = true;
      e.model_indices = match_parameters(ps, fp.id, "");
      for (size_t k : e.model_indices) {
        e.sens_columns.push_back(sens_params_.size());
        sens_params_.push_back(k);
      }
    }
    est_.push_back(fp);
    est_map_.push_back(e);
  }
}

// Targets: validate and label residuals.
void FitProblem::label_targets() {
  std::set<std::string> feats, values_only;
  target_features(model_, feats, values_only);
  for (auto& f : targets_.features) {
    if (values_only.count(f.feature)) {
      if (value_only_feature_.empty()) value_only_feature_ = f.feature;
    } else if (!feats.count(f.feature)) {
      std::string list, list2;
      for (auto& n : feats) list += (list.empty() ? "" : ", ") + n;
      for (auto& n : values_only) list2 += (list2.empty() ? "" : ", ") + n;
      throw Error(f.origin + ": unknown feature '" + f.feature + "' (features with exact gradients of this model: " + list +
                  (list2.empty() ? std::string(")") : "; values only, for derivative-free optimisers: " + list2 + ")"));
    }
    if (!(f.tolerance > 0)) throw Error(f.origin + ": tolerance must be > 0");
    if (!(settings_.t_end_ms > 0)) throw Error(f.origin + ": feature targets need t_end_ms in [fit] or [simulation]");
    labels_.push_back("feature " + f.feature);
  }
  for (size_t i = 0; i < targets_.switches.size(); ++i) {
    auto& s = targets_.switches[i];
    switch_channel_.push_back(find_channel(model_, s.channel, s.origin));
    if (!(s.time_ms > 0)) throw Error(s.origin + ": time_ms must be > 0");
    if (!(s.angle_tolerance_deg > 0)) throw Error(s.origin + ": angle_tolerance_deg must be > 0");
    const auto& ch = model_.angles()[switch_channel_.back()];
    deg_per_s(model_.states()[ch.velocity_state].unit, model_.states()[ch.velocity_state].name);
    std::string pre = "switch " + s.channel + " @" + format_g(s.time_ms) + "ms ";
    labels_.push_back(pre + "angle");
    if (s.velocity_tolerance_deg_s > 0) labels_.push_back(pre + "velocity");
    if (s.acceleration_tolerance_deg_s2 > 0) labels_.push_back(pre + "acceleration");
  }
  for (auto& k : targets_.kinematics) {
    if (!(k.sigma_deg > 0)) throw Error(k.origin + ": sigma_deg must be > 0");
    std::vector<size_t> chans;
    for (auto& c : k.data.channels) chans.push_back(find_channel(model_, c, k.origin));
    kin_channels_.push_back(chans);
    long oe = -1;
    double fixed = 0.0;
    if (!k.time_offset_parameter.empty()) {
      bool found = false;
      for (auto& fp : params_)
        if (fp.id == k.time_offset_parameter) {
          found = true;
          fixed = fp.nominal;
        }
      if (!found)
        throw Error(k.origin + ": time offset parameter '" + k.time_offset_parameter +
                    "' is not in the parameter table");
      for (size_t j = 0; j < est_.size(); ++j)
        if (est_[j].id == k.time_offset_parameter) oe = static_cast<long>(j);
    }
    offset_est_.push_back(oe);
    offset_fixed_.push_back(fixed);
    size_t used = 0;
    for (size_t c = 0; c < chans.size(); ++c)
      for (size_t s = 0; s < k.data.time_ms.size(); ++s)
        if (k.data.time_ms[s] >= k.t_min_ms && std::isfinite(k.data.angles_deg[c][s])) {
          labels_.push_back("data " + k.data.channels[c] + " @" + format_g(k.data.time_ms[s]) + "ms");
          ++used;
        }
    if (used == 0) throw Error(k.origin + ": no usable samples (all missing or before t_min_ms)");
  }
  label_step_cycles();
}

std::string FitProblem::no_jacobian_reason() const {
  return "the target feature '" + value_only_feature_ + "' is a class without gradients";
}

std::string FitProblem::parameter_unit(size_t j) const {
  if (!est_map_.at(j).is_model) return est_map_[j].unit;
  return model_.parameters().at(est_map_[j].model_indices.front()).unit;
}

std::vector<std::string> FitProblem::tied_parameters(size_t j) const {
  std::vector<std::string> n;
  for (size_t k : est_map_.at(j).model_indices) n.push_back(model_.parameters().at(k).name);
  return n;
}

std::vector<double> FitProblem::model_parameters(const double* x) const {
  std::vector<double> p = base_p_;
  for (size_t j = 0; j < est_.size(); ++j)
    for (size_t k : est_map_[j].model_indices) p[k] = from_scaled(est_[j].scale, x[j]);
  return p;
}

double FitProblem::horizon_ms(const double* x) const {
  double t = settings_.t_end_ms;
  for (auto& s : targets_.switches) t = std::max(t, s.time_ms);
  for (size_t i = 0; i < targets_.kinematics.size(); ++i) {
    double off = offset_est_[i] >= 0 ? x[offset_est_[i]] : offset_fixed_[i];
    t = std::max(t, targets_.kinematics[i].data.time_ms.back() + off);
  }
  return t;
}

FitProblem::Run FitProblem::run(const double* x, bool with_sens) const {
  Run R;
  R.p = model_parameters(x);
  std::vector<double> times;
  const double t_end = horizon_ms(x);
  times.push_back(t_end);
  for (auto& s : targets_.switches) times.push_back(s.time_ms);
  for (size_t i = 0; i < targets_.kinematics.size(); ++i) {
    double off = offset_est_[i] >= 0 ? x[offset_est_[i]] : offset_fixed_[i];
    R.offsets.push_back(off);
    for (double t : targets_.kinematics[i].data.time_ms) {
      if (t + off < 0)
        throw Error("time offset " + format_g(off) + " ms moves the sample at " + format_g(t) + " ms before the start of the simulation");
      times.push_back(t + off);
    }
  }
  for (const auto& t : targets_.step_cycles)  // dense outputs over the analysed steps
    for (double s = settings_.discard_ms; s < t_end; s += t.sample_ms) times.push_back(s);
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  R.out_times = times;
  for (auto& s : targets_.switches) R.switch_out.push_back(R.index_of(s.time_ms));
  for (size_t i = 0; i < targets_.kinematics.size(); ++i) {
    std::vector<size_t> idx;
    for (double t : targets_.kinematics[i].data.time_ms) idx.push_back(R.index_of(t + R.offsets[i]));
    R.kin_out.push_back(idx);
  }
  solver::Simulator sim(model_, settings_.solver);
  std::vector<solver::RootSpec> roots;
  if (!targets_.features.empty() || !targets_.step_cycles.empty()) roots = features::feature_roots(model_, R.p);
  R.res = sim.run(R.p, times, roots, with_sens ? sens_params_ : std::vector<size_t>{});
  features::check_joint_ranges(model_, R.res);  // a run beyond them is a failed evaluation
  if (R.res.t.size() != times.size()) throw SolverError("internal: simulation returned too few outputs");
  return R;
}

bool FitProblem::evaluate(const double* x, double* r, double* J, std::string* error) const {
  ++evaluations_;
  if (J) ++jacobian_evaluations_;
  const size_t n = est_.size(), m = labels_.size(), ns = sens_params_.size();
  try {
    for (size_t j = 0; j < n; ++j)
      if (!std::isfinite(x[j])) throw Error("non-finite parameter value for '" + est_[j].id + "'");
    const bool sens = J != nullptr && ns > 0;
    Run R = run(x, sens);
    const auto& res = R.res;
    const size_t nst = model_.num_states();
    // dr/dtheta (model columns via sensitivity columns; offset columns separately), row-major m x n.
    std::vector<double> dth(J ? m * n : 0, 0.0);
    auto set_model_row = [&](size_t row, auto&& dsens /* column c -> value */) {
      for (size_t j = 0; j < n; ++j)
        for (size_t c : est_map_[j].sens_columns) dth[row * n + j] += dsens(c);  // tied parameters: sum
    };
    size_t row = 0;

    if (!targets_.features.empty()) {
      features::FeatureOptions fo = settings_.feature_options;
      fo.discard_ms = settings_.discard_ms;
      fo.root_offset = 0;
      std::vector<features::FeatureGradient> fg;
      if (sens) {
        fg = features::compute_feature_gradients(model_, res, fo);
      } else {
        for (auto& f : features::compute_features(model_, res, fo)) fg.push_back({f, Eigen::VectorXd::Zero(ns)});
      }
      for (auto& t : targets_.features) {
        auto it = std::find_if(fg.begin(), fg.end(), [&](const features::FeatureGradient& g) { return g.feature.name == t.feature; });
        if (it == fg.end())
          throw Error("feature '" + t.feature + "' could not be computed (too few cycles after discard_ms, or no rhythm)");
        r[row] = (it->feature.value - t.value) / t.tolerance;
        if (J) set_model_row(row, [&](size_t c) { return it->gradient[c] / t.tolerance; });
        ++row;
      }
    }

    for (size_t i = 0; i < targets_.switches.size(); ++i) {
      const auto& s = targets_.switches[i];
      const auto& ch = model_.angles()[switch_channel_[i]];
      const size_t k = R.switch_out[i];
      const double vfac = deg_per_s(model_.states()[ch.velocity_state].unit, model_.states()[ch.velocity_state].name);
      r[row] = (res.state(k, ch.angle_state) * units::kDegPerRad - s.angle_deg) / s.angle_tolerance_deg;
      if (J && sens) set_model_row(row, [&](size_t c) { return res.sens(k, ch.angle_state, c) * units::kDegPerRad / s.angle_tolerance_deg; });
      ++row;
      if (s.velocity_tolerance_deg_s > 0) {
        r[row] = res.state(k, ch.velocity_state) * vfac / s.velocity_tolerance_deg_s;
        if (J && sens)
          set_model_row(row, [&](size_t c) { return res.sens(k, ch.velocity_state, c) * vfac / s.velocity_tolerance_deg_s; });
        ++row;
      }
      if (s.acceleration_tolerance_deg_s2 > 0) {
        // Left limit at T_sw: the right-hand side of the phase that ends at T_sw.
        const double te = s.time_ms - 1e-6 * std::max(1.0, s.time_ms);
        const double afac = vfac * 1000.0 / s.acceleration_tolerance_deg_s2;  // (unit/ms) -> deg/s^2
        std::vector<double> y(res.y.begin() + k * nst, res.y.begin() + (k + 1) * nst), f(nst);
        model_.rhs(te, y.data(), R.p.data(), f.data());
        r[row] = f[ch.velocity_state] * afac;
        if (J && sens) {
          std::vector<model::Jet1> y1(nst), p1(R.p.size()), f1(nst);
          for (size_t q = 0; q < R.p.size(); ++q) p1[q] = model::Jet1(R.p[q]);
          std::vector<double> col(ns);
          for (size_t c = 0; c < ns; ++c) {
            for (size_t q = 0; q < nst; ++q) {
              y1[q] = model::Jet1(y[q]);
              y1[q].v[0] = res.sens(k, q, c);
            }
            p1[sens_params_[c]].v[0] = 1.0;
            model_.rhs(te, y1.data(), p1.data(), f1.data());
            p1[sens_params_[c]].v[0] = 0.0;
            col[c] = f1[ch.velocity_state].v[0] * afac;
          }
          set_model_row(row, [&](size_t c) { return col[c]; });
        }
        ++row;
      }
    }

    std::vector<double> y(nst), f(nst);
    for (size_t i = 0; i < targets_.kinematics.size(); ++i) {
      const auto& kt = targets_.kinematics[i];
      const auto& chans = kin_channels_[i];
      for (size_t c = 0; c < chans.size(); ++c) {
        const auto& ch = model_.angles()[chans[c]];
        for (size_t sidx = 0; sidx < kt.data.time_ms.size(); ++sidx) {
          const double d = kt.data.angles_deg[c][sidx];
          if (!(kt.data.time_ms[sidx] >= kt.t_min_ms) || !std::isfinite(d)) continue;
          const size_t k = R.kin_out[i][sidx];
          r[row] = (res.state(k, ch.angle_state) * units::kDegPerRad - d) / kt.sigma_deg;
          if (J) {
            if (sens) set_model_row(row, [&](size_t col) { return res.sens(k, ch.angle_state, col) * units::kDegPerRad / kt.sigma_deg; });
            if (offset_est_[i] >= 0) {
              for (size_t q = 0; q < nst; ++q) y[q] = res.state(k, q);
              model_.rhs(res.t[k], y.data(), R.p.data(), f.data());
              dth[row * n + offset_est_[i]] = f[ch.angle_state] * units::kDegPerRad / kt.sigma_deg;  // deg/ms per ms
            }
          }
          ++row;
        }
      }
    }
    row = step_cycle_rows(R.res, x, sens, row, r, dth);
    if (row != m) throw Error("internal: residual count mismatch");
    for (size_t q = 0; q < m; ++q)
      if (!std::isfinite(r[q])) throw Error("non-finite residual '" + labels_[q] + "'");
    if (J) {
      for (size_t j = 0; j < n; ++j) {
        const double s = dtheta_dx(est_[j].scale, x[j]);
        for (size_t q = 0; q < m; ++q) J[q * n + j] = dth[q * n + j] * s;
      }
    }
    return true;
  } catch (const Error& e) {
    if (error) *error = e.what();
    return false;
  }
}

bool FitProblem::jacobian_fd(const double* x, double* J, double h, std::string* error) const {
  const size_t n = est_.size(), m = labels_.size();
  std::vector<double> xp(x, x + n), rp(m), rm(m);
  for (size_t j = 0; j < n; ++j) {
    const double step = h * std::max(1.0, std::abs(x[j]));
    xp[j] = x[j] + step;
    if (!evaluate(xp.data(), rp.data(), nullptr, error)) return false;
    xp[j] = x[j] - step;
    if (!evaluate(xp.data(), rm.data(), nullptr, error)) return false;
    xp[j] = x[j];
    for (size_t q = 0; q < m; ++q) J[q * n + j] = (rp[q] - rm[q]) / (2 * step);
  }
  return true;
}

solver::SolveResult FitProblem::simulate(const double* x, double dt_ms) const {
  std::vector<double> p = model_parameters(x);
  solver::Simulator sim(model_, settings_.solver);
  return sim.run(p, solver::output_grid(horizon_ms(x), dt_ms), features::feature_roots(model_, p));
}

std::vector<FitProblem::KinematicComparison> FitProblem::kinematic_comparison(const double* x) const {
  std::vector<KinematicComparison> out;
  if (targets_.kinematics.empty()) return out;
  Run R = run(x, false);
  for (size_t i = 0; i < targets_.kinematics.size(); ++i) {
    const auto& kt = targets_.kinematics[i];
    KinematicComparison c;
    c.time_ms = kt.data.time_ms;
    c.channels = kt.data.channels;
    c.data_deg = kt.data.angles_deg;
    for (size_t ch = 0; ch < kin_channels_[i].size(); ++ch) {
      const auto& a = model_.angles()[kin_channels_[i][ch]];
      std::vector<double> v;
      for (size_t s = 0; s < kt.data.time_ms.size(); ++s) v.push_back(R.res.state(R.kin_out[i][s], a.angle_state) * units::kDegPerRad);
      c.model_deg.push_back(v);
    }
    out.push_back(std::move(c));
  }
  return out;
}

void FitProblem::write_model_output(io::H5Writer& out, const double* x, bool usable, double output_dt_ms) const {
  if (!usable) {
    io::write_parameters(out, model_, model_parameters(x));
    return;
  }
  auto comps = kinematic_comparison(x);
  for (size_t i = 0; i < comps.size(); ++i) {
    const std::string suffix = i == 0 ? "" : "_" + std::to_string(i);
    out.write("/fit/data" + suffix + "/time", comps[i].time_ms, "ms");
    out.write("/fit/model" + suffix + "/time", comps[i].time_ms, "ms");
    for (size_t c = 0; c < comps[i].channels.size(); ++c) {
      out.write("/fit/data" + suffix + "/" + comps[i].channels[c], comps[i].data_deg[c], "deg");
      out.write("/fit/model" + suffix + "/" + comps[i].channels[c], comps[i].model_deg[c], "deg");
    }
  }
  write_step_comparison(out, x);
  solver::SolveResult tr = simulate(x, output_dt_ms);
  io::write_trajectory(out, model_, tr);
  io::write_parameters(out, model_, model_parameters(x));
  features::FeatureOptions fo = settings_.feature_options;
  fo.discard_ms = settings_.discard_ms;
  features::write_features_h5(out, features::compute_features(model_, tr, fo));
}

void FitProblem::write_step_comparison(io::H5Writer& out, const double* x) const {
  if (!targets_.step_cycles.empty()) write_step_cycles(out, run(x, false).res, x);
}

}  // namespace phasmid::fit
