// FitProblem's step-cycle targets (fit/targets.hpp, docs/recordings.md): a recording's mean
// angle per phase bin, its median period and duty factor against the model's step cycle of one
// leg (features/model_step_cycle.hpp), through affine observables.
#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "common/format.hpp"
#include "features/model_step_cycle.hpp"
#include "fit/fit_problem.hpp"
#include "io/h5_file.hpp"

namespace phasmid::fit {
namespace {


size_t index_of(const std::vector<std::string>& names, const std::string& name, const std::string& what) {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return i;
  std::string have;
  for (auto& n : names) have += (have.empty() ? "" : ", ") + n;
  throw Error(what + " (it has: " + have + ")");
}

// The noise of bin k of data channel c: the observable's noise parameter (sigma > 0), its fixed
// sigma_deg, else the recording's SD (floored).
double bin_sigma(const StepCycleTarget& t, const Observable& o, size_t c, size_t k, double sigma) {
  if (sigma > 0) return sigma;
  return o.sigma_deg > 0 ? o.sigma_deg : t.bin_sd_deg(c, k);
}

}  // namespace

// An observable's offset or scale: (index of its estimate or -1, its fixed or starting value).
std::pair<long, double> FitProblem::observable_parameter(const std::string& id, double value, const std::string& origin,
                                                         const char* what) const {
  if (id.empty()) return {-1, value};
  auto fp = std::find_if(params_.begin(), params_.end(), [&](const FitParameter& p) { return p.id == id; });
  if (fp == params_.end()) throw Error(origin + ": " + what + " parameter '" + id + "' is not in the parameter table");
  for (size_t j = 0; j < est_.size(); ++j)
    if (est_[j].id == id) return {static_cast<long>(j), fp->nominal};
  return {-1, fp->nominal};
}

// Observable o of a target at estimates x: the model's profile index, the recording's channel,
// the offset, the scale and the noise parameter's value (0: none).
FitProblem::ObservableAt FitProblem::observable_at(const features::ModelStepCycle& mc, const StepCycleMap& m, size_t o,
                                                   const double* x) const {
  const auto mch = std::find(mc.channels.begin(), mc.channels.end(), m.model_channel[o]) - mc.channels.begin();
  return {static_cast<size_t>(mch), m.data_channel[o], offset_value(m.offset_est[o], m.offset_fixed[o], x),
          offset_value(m.scale_est[o], m.scale_fixed[o], x), theta_value(m.sigma_est[o], m.sigma_fixed[o], x)};
}

void FitProblem::label_step_cycles() {
  std::vector<std::string> model_channels;
  for (const auto& a : model_.angles()) model_channels.push_back(a.leg + "." + a.joint);
  for (const auto& t : targets_.step_cycles) {
    if (!(settings_.t_end_ms > settings_.discard_ms))
      throw Error(t.origin + ": recording targets need t_end_ms above discard_ms in [fit] (the model's steps lie between)");
    if (!model_.contact_leg(t.model_leg)) throw Error(t.origin + ": the model has no ground contact for leg '" + t.model_leg + "'");
    if (!(t.sample_ms > 0)) throw Error(t.origin + ": sample_ms must be > 0");
    if (!(t.period_noise_ms() > 0) || !(t.duty_factor_noise() > 0))
      throw Error(t.origin + ": the recording's period and duty factor have no step-to-step SD (" +
                  std::to_string(t.data.kept()) + " step kept); give period_sigma_ms and duty_factor_sigma");
    StepCycleMap m;
    for (const auto& o : t.observables) {
      m.model_channel.push_back(index_of(model_channels, o.model_channel, o.origin + ": the model has no angle '" + o.model_channel + "'"));
      if (model_.angles()[m.model_channel.back()].leg != t.model_leg)
        throw Error(o.origin + ": '" + o.model_channel + "' is not an angle of the model's leg '" + t.model_leg + "'");
      m.data_channel.push_back(index_of(t.data.channels, o.data_channel, o.origin + ": the recording has no channel '" + o.data_channel + "'"));
      if (o.sign != 1 && o.sign != -1) throw Error(o.origin + ": sign must be 1 or -1");
      const auto [off_est, off_fixed] = observable_parameter(o.offset_parameter, o.offset_deg, o.origin, "offset");
      const auto [scale_est, scale_fixed] = observable_parameter(o.scale_parameter, o.scale, o.origin, "scale");
      m.offset_est.push_back(off_est);
      m.offset_fixed.push_back(off_fixed);
      m.scale_est.push_back(scale_est);
      m.scale_fixed.push_back(scale_fixed);
      const auto [sigma_est, sigma_fixed] = observable_parameter(o.sigma_parameter, 0, o.origin, "noise");
      m.sigma_est.push_back(sigma_est);
      m.sigma_fixed.push_back(sigma_fixed);
      const FitParameter* noise = sigma_est >= 0 ? &est_[static_cast<size_t>(sigma_est)] : nullptr;
      m.noise_centre.push_back(noise ? 0.5 * std::log(noise->lower * noise->upper) : 0);
      m.noise_span.push_back(noise ? 0.75 * std::log(noise->upper / noise->lower) : 0);
      if (noise && !(noise->upper > noise->lower))
        throw Error(o.origin + ": noise parameter '" + noise->id + "' needs an upper bound above its lower bound");
      for (size_t k = 0; k < t.data.phase.size(); ++k) {
        if (!(bin_sigma(t, o, m.data_channel.back(), k, sigma_fixed) > 0) && sigma_est < 0)
          throw Error(o.origin + ": no noise for '" + o.data_channel + "' (the recording's SD needs two steps; give sigma_deg)");
        labels_.push_back("steps " + o.data_channel + " @" + format_g(t.data.phase[k]));
      }
      if (sigma_est >= 0) {
        labels_.push_back("steps " + o.data_channel + " noise");
        labels_.push_back("steps " + o.data_channel + " noise bound");
      }
    }
    labels_.push_back("steps " + t.leg + " period");
    labels_.push_back("steps " + t.leg + " duty_factor");
    step_maps_.push_back(std::move(m));
  }
}

// An estimated noise sigma shared by n bins adds n ln(sigma) to the negative log-likelihood
// 1/2 sum r^2 + n ln(sigma). With t = ln(sigma / sigma0) it enters as two residuals,
//   e1 = sqrt(n) (t + 1),  e2 = sqrt(n) sqrt(M^2 - t^2),  1/2 (e1^2 + e2^2) = n t + const,
// whose Gauss-Newton curvature in sigma, n / sigma^2 (1 + t^2 / (M^2 - t^2)), is the
// likelihood's n / sigma^2 at sigma0 and close to it nearby. (Data2Dynamics' single residual
// sqrt(2 ln sigma + c) has curvature 1 / (sigma^2 e^2), exact only where e = 1, and a
// Gauss-Newton iteration in sigma that converges slowly elsewhere.) sigma0 is the geometric
// middle of sigma's bounds and M 1.5 times their half-width in ln(sigma), so e2 stays real
// inside them and a little beyond.
size_t FitProblem::noise_rows(const StepCycleMap& m, size_t o, double sigma, size_t n_bins, size_t row, double* r,
                              std::vector<double>& dth) const {
  const double sn = std::sqrt(static_cast<double>(n_bins)), t = std::log(sigma) - m.noise_centre[o], M = m.noise_span[o];
  if (!(std::abs(t) < M))
    throw Error("noise parameter '" + est_[static_cast<size_t>(m.sigma_est[o])].id + "' at " + format_g(sigma) +
                " deg, far outside its bounds");
  r[row] = sn * (t + 1);
  r[row + 1] = sn * std::sqrt(M * M - t * t);
  if (!dth.empty()) {
    const size_t j = static_cast<size_t>(m.sigma_est[o]), n = est_.size();
    dth[row * n + j] = sn / sigma;
    dth[(row + 1) * n + j] = -sn * t / (sigma * std::sqrt(M * M - t * t));
  }
  return row + 2;
}

size_t FitProblem::step_cycle_rows(const solver::SolveResult& res, const double* x, bool sens, size_t row, double* r,
                                   std::vector<double>& dth) const {
  if (targets_.step_cycles.empty()) return row;
  const size_t n = est_.size();
  features::FeatureOptions fo = settings_.feature_options;
  fo.discard_ms = settings_.discard_ms;
  fo.root_offset = 0;
  auto model_row = [&](size_t q, const Eigen::VectorXd& g, double factor) {
    for (size_t j = 0; j < n; ++j)
      for (size_t c : est_map_[j].sens_columns) dth[q * n + j] += g[static_cast<long>(c)] * factor;
  };
  for (size_t i = 0; i < targets_.step_cycles.size(); ++i) {
    const StepCycleTarget& t = targets_.step_cycles[i];
    const StepCycleMap& m = step_maps_[i];
    const features::ModelStepCycle mc = features::model_step_cycle(model_, res, t.model_leg, static_cast<int>(t.data.phase.size()), fo, sens);
    for (size_t o = 0; o < t.observables.size(); ++o) {
      const Observable& ob = t.observables[o];
      const auto [mch, dch, off, scale, sigma] = observable_at(mc, m, o, x);
      for (size_t k = 0; k < t.data.phase.size(); ++k, ++row) {
        const double s = bin_sigma(t, ob, dch, k, sigma);
        r[row] = (ob.sign * scale * mc.mean_deg[mch][k] + off - t.data.mean_deg[dch][k]) / s;
        if (dth.empty()) continue;
        if (sens) model_row(row, mc.dmean_deg[mch][k], ob.sign * scale / s);
        if (m.offset_est[o] >= 0) dth[row * n + static_cast<size_t>(m.offset_est[o])] = 1 / s;
        if (m.scale_est[o] >= 0) dth[row * n + static_cast<size_t>(m.scale_est[o])] = ob.sign * mc.mean_deg[mch][k] / s;
        if (m.sigma_est[o] >= 0) dth[row * n + static_cast<size_t>(m.sigma_est[o])] = -r[row] / s;
      }
      if (m.sigma_est[o] >= 0) row = noise_rows(m, o, sigma, t.data.phase.size(), row, r, dth);
    }
    r[row] = (mc.period_ms - t.data.mean_period_ms) / t.period_noise_ms();
    if (sens && !dth.empty()) model_row(row, mc.dperiod_ms, 1 / t.period_noise_ms());
    ++row;
    r[row] = (mc.duty_factor - t.data.duty_factor) / t.duty_factor_noise();
    if (sens && !dth.empty()) model_row(row, mc.dduty_factor, 1 / t.duty_factor_noise());
    ++row;
  }
  return row;
}

// /fit/steps/<i>/: the recording's and the model's profiles (through the observables), with
// the noise per bin, and the periods and duty factors as attributes (docs/hdf5.md).
void FitProblem::write_step_cycles(io::H5Writer& out, const solver::SolveResult& res, const double* x) const {
  features::FeatureOptions fo = settings_.feature_options;
  fo.discard_ms = settings_.discard_ms;
  for (size_t i = 0; i < targets_.step_cycles.size(); ++i) {
    const StepCycleTarget& t = targets_.step_cycles[i];
    const StepCycleMap& m = step_maps_[i];
    const features::ModelStepCycle mc = features::model_step_cycle(model_, res, t.model_leg, static_cast<int>(t.data.phase.size()), fo, false);
    const std::string g = "/fit/steps/" + std::to_string(settings_.step_output_base + i);
    out.write(g + "/phase", t.data.phase, "1");
    for (size_t o = 0; o < t.observables.size(); ++o) {
      const Observable& ob = t.observables[o];
      const auto [mch, dch, off, scale, noise] = observable_at(mc, m, o, x);
      std::vector<double> model, sigma;
      for (size_t k = 0; k < t.data.phase.size(); ++k) {
        model.push_back(ob.sign * scale * mc.mean_deg[mch][k] + off);
        sigma.push_back(bin_sigma(t, ob, dch, k, noise));
      }
      out.write(g + "/data_mean/" + ob.data_channel, t.data.mean_deg[dch], "deg");
      out.write(g + "/data_sd/" + ob.data_channel, t.data.sd_deg[dch], "deg");
      out.write(g + "/model/" + ob.data_channel, model, "deg");
      out.write(g + "/sigma/" + ob.data_channel, sigma, "deg");
      out.set_attribute(g + "/model/" + ob.data_channel, "model_channel", ob.model_channel);
    }
    out.set_attribute(g, "file", t.file);
    if (!settings_.condition.empty()) out.set_attribute(g, "condition", settings_.condition);
    out.set_attribute(g, "leg", t.leg);
    out.set_attribute(g, "model_leg", t.model_leg);
    out.set_attribute(g, "data_period_ms", t.data.mean_period_ms);
    out.set_attribute(g, "data_median_period_ms", t.data.median_period_ms);
    out.set_attribute(g, "model_period_ms", mc.period_ms);
    out.set_attribute(g, "data_duty_factor", t.data.duty_factor);
    out.set_attribute(g, "model_duty_factor", mc.duty_factor);
    out.set_attribute(g, "period_sigma_ms", t.period_noise_ms());
    out.set_attribute(g, "duty_factor_sigma", t.duty_factor_noise());
    out.set_attribute(g, "data_steps", static_cast<double>(t.data.kept()));
    out.set_attribute(g, "model_steps", static_cast<double>(mc.steps));
  }
}

}  // namespace phasmid::fit
