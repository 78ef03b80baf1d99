#include "cruse/cruse1980_fit.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "common/error.hpp"
#include "cruse/cruse1980_model.hpp"
#include "cruse/cruse1980_output.hpp"
#include "cruse/cruse1980_sweep.hpp"
#include "fit/parameter_table.hpp"
#include "io/h5_file.hpp"

namespace phasmid::cruse {
namespace {

int leg_index(const std::string& name) {
  const auto& names = leg_names();
  auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

// Circular distance of two phases (fractions of a period).
double circular(double a, double b) {
  double d = std::fmod(std::abs(a - b), 1.0);
  return std::min(d, 1.0 - d);
}

const std::vector<std::string>& switch_names() {
  static const std::vector<std::string> s = {"SL", "SR", "SL1R1"};
  return s;
}

std::string node_name(const std::string& which, double period) {
  return "switch." + which + ".at_" + std::to_string(static_cast<int>(period)) + "ms";
}

std::string run_feature_list() {
  return "locked, period_ms, lag_L3_L1_ms, lag_R3_R1_ms, lag_difference_ms, phase.<leg>, gap_ms.<A>-<B>, "
         "pattern_deviation_ms, wave_excess_ms (with period_ms); switch_reversal.SL|SR|SL1R1 (without)";
}

}  // namespace

bool is_run_feature(const std::string& name) {
  static const std::set<std::string> plain = {"locked",       "period_ms",         "lag_L3_L1_ms",
                                              "lag_R3_R1_ms", "lag_difference_ms", "pattern_deviation_ms",
                                              "wave_excess_ms"};
  if (plain.count(name)) return true;
  if (name.rfind("phase.", 0) == 0) return leg_index(name.substr(6)) >= 0;
  if (name.rfind("gap_ms.", 0) == 0) {
    const std::string pair = name.substr(7);
    const auto dash = pair.find('-');
    return dash != std::string::npos && leg_index(pair.substr(0, dash)) >= 0 && leg_index(pair.substr(dash + 1)) >= 0;
  }
  return false;
}

bool is_parameter_feature(const std::string& name) {
  if (name.rfind("switch_reversal.", 0) != 0) return false;
  const auto& s = switch_names();
  return std::find(s.begin(), s.end(), name.substr(16)) != s.end();
}

double run_feature(const std::string& name, const Features& f, const Features& first) {
  if (name == "locked") return f.locked ? 1.0 : 0.0;
  if (name == "period_ms") return f.period_ms;
  if (name == "lag_L3_L1_ms") return f.lag_L3_L1_ms;
  if (name == "lag_R3_R1_ms") return f.lag_R3_R1_ms;
  if (name == "lag_difference_ms") return f.lag_R3_R1_ms - f.lag_L3_L1_ms;
  if (name == "pattern_deviation_ms") {
    double d = std::abs(f.period_ms - first.period_ms);
    for (int leg = 0; leg < kLegCount; ++leg) d = std::max(d, circular(f.phase[leg], first.phase[leg]) * f.period_ms);
    return d;
  }
  if (name == "wave_excess_ms") {
    // Per side: hind -> middle delay plus middle -> front delay beyond one period means the
    // metachronal wave runs front to back instead.
    auto ahead = [&](int from, int to) { return std::fmod(f.phase[to] - f.phase[from] + 2.0, 1.0) * f.period_ms; };
    return std::max(0.0, ahead(L3, L2) + ahead(L2, L1) - f.period_ms) +
           std::max(0.0, ahead(R3, R2) + ahead(R2, R1) - f.period_ms);
  }
  if (name.rfind("phase.", 0) == 0) return f.phase.at(static_cast<size_t>(leg_index(name.substr(6))));
  if (name.rfind("gap_ms.", 0) == 0) {
    const std::string pair = name.substr(7);
    const auto dash = pair.find('-');
    const int a = leg_index(pair.substr(0, dash)), b = leg_index(pair.substr(dash + 1));
    return circular(f.phase.at(static_cast<size_t>(a)), f.phase.at(static_cast<size_t>(b))) * f.period_ms;
  }
  throw Error("cruse1980: unknown run feature '" + name + "'");
}

double parameter_feature(const std::string& name, const Parameters& p) {
  if (!is_parameter_feature(name)) throw Error("cruse1980: unknown parameter feature '" + name + "'");
  const std::string which = name.substr(16);
  const auto& nodes = switch_node_periods();
  double reversal = 0;
  for (size_t i = 1; i < nodes.size(); ++i)
    reversal += std::max(0.0, p.get(node_name(which, nodes[i - 1])) - p.get(node_name(which, nodes[i])));
  return reversal;
}

CruseFitProblem::CruseFitProblem(Parameters base, std::vector<fit::FitParameter> parameters,
                                 std::vector<CruseTarget> targets, CruseFitSettings settings)
    : base_(std::move(base)), targets_(std::move(targets)), settings_(std::move(settings)) {
  params_ = std::move(parameters);
  std::set<std::string> seen;
  for (auto& fp : params_) {
    const std::string w = fp.origin.empty() ? "" : fp.origin + ": ";
    if (!seen.insert(fp.id).second) throw Error(w + "parameter '" + fp.id + "' given twice");
    fit::validate(fp);
    std::vector<std::string> names;
    for (const auto& np : base_.all())
      if (fit::parameter_id_matches(fp.id, np.name)) names.push_back(np.name);
    if (names.empty())
      throw Error(w + "unknown parameter '" + fp.id + "' of the cruse1980 model (`phasmid params CONFIG` lists them)");
    for (const auto& n : names) {
      if (n == "start_position" || n == "duration_ms" || n == "retraction_rate" || n == "analysis.cycles")
        throw Error(w + "'" + n + "' is set per run by the fit (period_ms, start_positions, cycles); it cannot be fitted");
      try {
        Parameters probe = base_;
        if (fp.estimate) {
          probe.set(n, fp.lower);
          probe.set(n, fp.upper);
        } else {
          base_.set(n, fp.nominal);
        }
      } catch (const Error& e) {
        throw Error(w + e.what());
      }
    }
    if (fp.estimate) {
      est_.push_back(fp);
      tied_.push_back(names);
    }
  }
  if (est_.empty()) throw Error("no parameter is estimated (set estimate = 1 for at least one)");
  if (targets_.empty()) throw Error("the fit has no targets (give [[fit.feature]])");
  if (settings_.start_positions.empty()) throw Error("start_positions is empty");
  for (int s : settings_.start_positions)
    if (s < 1 || s > 10) throw Error(fmt::format("start_positions: {} is not a Table 2 position (1..10)", s));
  const double need = base_.get("analysis.cycles") + 3;
  if (!(settings_.cycles >= need))
    throw Error(fmt::format("cycles must be at least analysis.cycles + 3 = {} (runs need a settled window)", need));
  for (const auto& t : targets_) {
    const std::string w = t.origin.empty() ? "" : t.origin + ": ";
    if (!(t.tolerance > 0)) throw Error(w + "tolerance must be > 0");
    if (is_parameter_feature(t.feature)) {
      if (t.period_ms != 0) throw Error(w + "'" + t.feature + "' is a parameter feature and takes no period_ms");
      labels_.push_back("feature " + t.feature);
      continue;
    }
    if (!is_run_feature(t.feature))
      throw Error(w + "unknown cruse1980 feature '" + t.feature + "' (features: " + run_feature_list() + ")");
    // Gait II: the protraction alone takes T0(OL1)/protraction_rate; the period must exceed it.
    const double shortest = base_.gait == Gait::II ? base_.t0(L1) / base_.get("protraction_rate") : 0.0;
    if (!(t.period_ms > shortest)) throw Error(w + fmt::format("period_ms must exceed {} ms", shortest));
    if (std::find(periods_.begin(), periods_.end(), t.period_ms) == periods_.end()) periods_.push_back(t.period_ms);
    for (int s : settings_.start_positions)
      labels_.push_back(fmt::format("feature {} @{}ms start {}", t.feature, t.period_ms, s));
  }
}

std::string CruseFitProblem::parameter_unit(size_t j) const {
  const std::string& n = tied_.at(j).front();
  for (const auto& np : base_.all())
    if (np.name == n) return np.unit;
  return "";
}

std::vector<std::string> CruseFitProblem::tied_parameters(size_t j) const { return tied_.at(j); }

std::string CruseFitProblem::no_jacobian_reason() const {
  return "the cruse1980 oscillators are piecewise linear with discrete phase decisions, so features jump "
         "or are flat in the parameters";
}

Parameters CruseFitProblem::parameters_at(const double* x) const {
  Parameters p = base_;
  for (size_t j = 0; j < est_.size(); ++j) {
    const double v = fit::from_scaled(est_[j].scale, x[j]);
    for (const auto& n : tied_[j]) p.set(n, v);
  }
  return p;
}

bool CruseFitProblem::evaluate(const double* x, double* r, double* J, std::string* error) const {
  if (J) throw Error("internal: the cruse1980 fit has no Jacobian");
  try {
    const Parameters p = parameters_at(x);
    // Features of every run: per period, per starting position.
    std::vector<std::vector<Features>> runs(periods_.size());
    for (size_t k = 0; k < periods_.size(); ++k) {
      Parameters q = at_period(p, periods_[k], settings_.cycles);
      // Features need only the onsets: no dense output of event-exact runs.
      q.set("output_step_ms", settings_.cycles * periods_[k]);
      for (int s : settings_.start_positions) {
        q.set("start_position", s);
        runs[k].push_back(measure(simulate(q), q));
      }
    }
    size_t row = 0;
    for (const auto& t : targets_) {
      if (is_parameter_feature(t.feature)) {
        r[row++] = (parameter_feature(t.feature, p) - t.value) / t.tolerance;
        continue;
      }
      const size_t k = static_cast<size_t>(std::find(periods_.begin(), periods_.end(), t.period_ms) - periods_.begin());
      for (const Features& f : runs[k]) r[row++] = (run_feature(t.feature, f, runs[k].front()) - t.value) / t.tolerance;
    }
    return true;
  } catch (const Error& e) {
    if (error) *error = e.what();
    return false;
  }
}

void CruseFitProblem::write_model_output(io::H5Writer& out, const double* x, bool, double) const {
  const Parameters p = parameters_at(x);
  const Trajectory run = simulate(p);
  write_run_contents(out, p, run, measure(run, p));
}

}  // namespace phasmid::cruse
