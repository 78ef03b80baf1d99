// Model kind "cruse1980": the six coupled relaxation oscillators of Cruse (1980) as a scenario
// (docs/cruse1980.md). The run length and output step are the model's own parameters
// (duration_ms, output_step_ms), so [simulation] does not apply. With
// `stability_periods_ms = [...]` in [model] every run also reports `table1_stable`: 1 when at
// each of those nominal periods all ten Table 2 starting positions settle into one locked
// pattern with L1-R2 and L2-R3 in phase (the criterion of Cruse's Table 1).
#include <fmt/format.h>

#include <chrono>

#include "common/error.hpp"
#include "cruse/cruse1980_features.hpp"
#include "cruse/cruse1980_fit.hpp"
#include "cruse/cruse1980_model.hpp"
#include "cruse/cruse1980_output.hpp"
#include "cruse/cruse1980_sweep.hpp"
#include "fit/optimizer.hpp"
#include "scenario/registry.hpp"

namespace phasmid::scenario {
namespace {

using cruse::Parameters;

std::vector<features::Feature> feature_list(const cruse::Features& f) {
  std::vector<features::Feature> out = {{"locked", f.locked ? 1.0 : 0.0, "1"},
                                        {"period_ms", f.period_ms, "ms"},
                                        {"lag_L3_L1_ms", f.lag_L3_L1_ms, "ms"},
                                        {"lag_R3_R1_ms", f.lag_R3_R1_ms, "ms"}};
  for (int leg = 0; leg < cruse::kLegCount; ++leg)
    out.push_back({"phase." + cruse::leg_names()[leg], f.phase[leg], "1"});
  return out;
}

class CruseRun : public ScenarioRun {
 public:
  CruseRun(Parameters p, const std::vector<double>& periods) : p_(std::move(p)) {
    const auto t0 = std::chrono::steady_clock::now();
    traj_ = cruse::simulate(p_);
    feat_ = cruse::measure(traj_, p_);
    list_ = feature_list(feat_);
    if (!periods.empty()) list_.push_back({"table1_stable", cruse::is_stable(p_, periods) ? 1.0 : 0.0, "1"});
    seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  const std::vector<features::Feature>& features() const override { return list_; }
  void write(io::H5Writer& out) const override { cruse::write_run_contents(out, p_, traj_, feat_); }
  std::vector<std::string> notes() const override {
    std::string pairs;
    for (const auto& pair : feat_.in_phase_pairs) pairs += " " + pair;
    return {fmt::format("locked {}  period {:.1f} ms  lag L3->L1 {:.1f} ms  lag R3->R1 {:.1f} ms  in phase:{}",
                        feat_.locked ? "yes" : "no", feat_.period_ms, feat_.lag_L3_L1_ms, feat_.lag_R3_R1_ms, pairs)};
  }
  std::string summary() const override {
    return fmt::format("six oscillators, {:g} ms in {:g} s", p_.get("duration_ms"), seconds_);
  }

 private:
  Parameters p_;
  cruse::Trajectory traj_;
  cruse::Features feat_;
  std::vector<features::Feature> list_;
  double seconds_ = 0;
};

class CruseScenario : public Scenario {
 public:
  CruseScenario(Parameters base, std::vector<double> stability_periods)
      : base_(std::move(base)), periods_(std::move(stability_periods)) {
    for (const auto& q : base_.all()) {
      model::Parameter p{q.name, q.value, q.unit, q.source, ""};
      if (q.unit == "ms" || q.unit == "unit/ms") p.lower = 0;  // run lengths and rates
      if (q.name == "start_position") p.lower = 1, p.upper = 10;  // rows of Table 2
      params_.add(p);
    }
  }
  std::string kind() const override { return "cruse1980"; }
  model::ParameterSet& parameters() override { return params_; }
  bool takes_simulation_settings() const override { return false; }
  std::vector<features::FeatureInfo> feature_catalogue() const override {
    std::vector<features::FeatureInfo> c = {
        {"locked", "1", false, "1 when every leg steps once per OL1 period throughout the analysis window"},
        {"period_ms", "ms", false, "period of OL1 over the analysis window"},
        {"lag_L3_L1_ms", "ms", false, "Graham's lag: L3 protraction onset to the next L1 onset"},
        {"lag_R3_R1_ms", "ms", false, "Graham's lag: R3 protraction onset to the next R1 onset"}};
    for (const auto& leg : cruse::leg_names())
      c.push_back({"phase." + leg, "1", false, "protraction onset of " + leg + " after OL1's, fraction of the period"});
    if (!periods_.empty())
      c.push_back({"table1_stable", "1", false,
                   "1 when at every stability period all ten Table 2 starts lock into one pattern with L1-R2, L2-R3 in phase"});
    return c;
  }

  // The base parameters with the vector's values; Parameters::set refuses what the model
  // cannot run (a start position outside Table 2, a non-positive rate).
  Parameters at(const std::vector<double>& p) const {
    Parameters q = base_;
    for (size_t i = 0; i < p.size(); ++i) q.set(params_.at(i).name, p[i]);
    return q;
  }
  std::unique_ptr<ScenarioRun> run(const std::vector<double>& p, const RunSettings&) const override {
    return std::make_unique<CruseRun>(at(p), periods_);
  }
  // `spec.kind` holds the cruse1980 targets (config/cruse_section.hpp reads them from [fit]).
  std::unique_ptr<fit::ResidualProblem> make_fit(const fit::FitSpec& spec) const override {
    const auto* own = dynamic_cast<const cruse::CruseFitSpec*>(spec.kind.get());
    if (!own) throw Error("cruse1980: the fit spec has no cruse1980 targets (read [fit] with config::fit_spec)");
    auto problem = std::make_unique<cruse::CruseFitProblem>(at(params_.values()), spec.parameters, own->targets,
                                                            own->settings);
    fit::check_optimizer(*problem, spec.optimizer);
    return problem;
  }

 private:
  Parameters base_;
  model::ParameterSet params_;
  std::vector<double> periods_;
};

std::vector<double> stability_periods(const ModelSection& s) {
  std::vector<double> periods;
  for (const auto& e : s.numbers("stability_periods_ms", "a list of periods (ms)")) {
    if (!(e.value > 0)) throw Error(e.where + ": stability_periods_ms: a period must be > 0 ms");
    periods.push_back(e.value);
  }
  return periods;
}

}  // namespace

ModelKind cruse1980_kind() {
  return {"cruse1980", "Cruse (1980): six coupled relaxation oscillators of leg coordination",
          {"gait", "time_stepping", "stability_periods_ms"}, [](const ModelSection& s) -> std::unique_ptr<Scenario> {
            Parameters p;
            p.gait = s.choice("gait", "II", {"I", "II"}) == "I" ? cruse::Gait::I : cruse::Gait::II;
            p.stepping = s.choice("time_stepping", "raster", {"raster", "continuous"}) == "raster"
                             ? cruse::Stepping::Raster
                             : cruse::Stepping::Continuous;
            return std::make_unique<CruseScenario>(p, stability_periods(s));
          }};
}

}  // namespace phasmid::scenario
