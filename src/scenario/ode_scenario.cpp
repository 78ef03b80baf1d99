#include "scenario/ode_scenario.hpp"

#include <fmt/format.h>

#include "features/joint_range.hpp"
#include "features/missing_features.hpp"
#include "fit/fit_problem.hpp"
#include "fit/fit_spec.hpp"
#include "io/trajectory_writer.hpp"

namespace phasmid::scenario {
namespace {

// "front.touchdown" or, with in_stance, "front.touchdown with hind in stance".
std::string trigger_text(const model::CommandTrigger& tr) {
  std::string s = tr.event;
  for (size_t i = 0; i < tr.in_stance.size(); ++i)
    s += (i == 0 ? " with " : i + 1 == tr.in_stance.size() ? " and " : ", ") + tr.in_stance[i].leg;
  return tr.in_stance.empty() ? s : s + " in stance";
}

class OdeRun : public ScenarioRun {
 public:
  OdeRun(const model::OdeModel& m, std::vector<double> p, solver::SolveResult r, const RunSettings& s)
      : model_(m), p_(std::move(p)), result_(std::move(r)), t_end_ms_(s.t_end_ms),
        streamed_(s.solver.output_sink != nullptr) {
    features::FeatureOptions fo;
    fo.discard_ms = s.discard_ms;
    features_ = features::compute_features(model_, result_, fo);
    missing_ = features::add_missing_features(features_, features::feature_catalogue(model_));
    // Command times resolved by [[triggers]] are recorded with the values they took.
    for (const auto& c : result_.commands) p_[c.parameter] = c.t_ms;
  }
  const std::vector<features::Feature>& features() const override { return features_; }
  const solver::SolveResult* solution() const override { return streamed_ ? nullptr : &result_; }
  void write(io::H5Writer& out) const override {
    if (streamed_) io::write_solver_stats(out, result_.stats);  // the samples went to the sink
    else io::write_trajectory(out, model_, result_);
    io::write_parameters(out, model_, p_);
    features::write_features_h5(out, features_);
    features::mark_missing_features_h5(out, missing_);
  }
  // One line per triggered command time (its value reproduces the run with fixed times, e.g.
  // for `phasmid sensitivity`), and one per trigger that never fired.
  std::vector<std::string> notes() const override {
    const auto& triggers = model_.triggers();
    std::vector<std::string> lines;
    std::vector<bool> fired(triggers.size(), false);
    for (const auto& c : result_.commands) {
      fired[c.trigger] = true;
      lines.push_back(fmt::format("{} = {} ms (trigger {})", model_.parameters().at(c.parameter).name, c.t_ms,
                                  trigger_text(triggers[c.trigger])));
    }
    for (size_t k = 0; k < triggers.size(); ++k)
      if (!fired[k])
        lines.push_back("warning: trigger " + trigger_text(triggers[k]) + " for " +
                        model_.parameters().at(triggers[k].targets.front()).name +
                        " did not fire before the end of the run");
    if (!missing_.empty()) lines.push_back("warning: " + features::missing_features_note(missing_));
    return lines;
  }
  std::string summary() const override {
    const long parts = result_.stats.integrators;
    return fmt::format("{} states, {:g} ms in {:g} s{}", model_.num_states(), t_end_ms_, result_.stats.wall_seconds,
                       parts > 1 ? fmt::format(" ({} integrators, one per part)", parts) : "");
  }

 private:
  const model::OdeModel& model_;
  std::vector<double> p_;
  solver::SolveResult result_;
  double t_end_ms_;
  bool streamed_;
  std::vector<features::Feature> features_;
  std::vector<std::string> missing_;  // catalogue features the run could not compute (NaN)
};

}  // namespace

std::unique_ptr<ScenarioRun> OdeScenario::run(const std::vector<double>& p, const RunSettings& s) const {
  if (s.solver.output_sink) {
    features::JointRangeWatch watch(*model_, *s.solver.output_sink);
    RunSettings watched = s;
    watched.solver.output_sink = &watch;
    solver::Simulator sim(*model_, watched.solver);
    solver::SolveResult r =
        sim.run(p, solver::OutputTimes::grid(s.t_end_ms, s.output_dt_ms), features::feature_roots(*model_, p));
    watch.check(r);
    return std::make_unique<OdeRun>(*model_, p, std::move(r), s);
  }
  solver::Simulator sim(*model_, s.solver);
  solver::SolveResult r =
      sim.run(p, solver::output_grid(s.t_end_ms, s.output_dt_ms), features::feature_roots(*model_, p));
  features::check_joint_ranges(*model_, r);
  return std::make_unique<OdeRun>(*model_, p, std::move(r), s);
}

std::vector<features::Feature> OdeScenario::evaluate_features(const std::vector<double>& p,
                                                              const RunSettings& s) const {
  solver::Simulator sim(*model_, s.solver);
  // Features come from located events, so two output times suffice; CVODES steps the same
  // way whatever the output grid (it interpolates to output times in CV_NORMAL mode).
  solver::SolveResult r = sim.run(p, {0.0, s.t_end_ms}, features::feature_roots(*model_, p));
  features::check_joint_ranges(*model_, r);
  features::FeatureOptions fo;
  fo.discard_ms = s.discard_ms;
  return features::compute_features(*model_, r, fo);
}

std::vector<std::pair<std::string, std::string>> OdeScenario::run_time_parameters() const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& tr : model_->triggers())
    for (size_t k : tr.targets) out.emplace_back(model_->parameters().at(k).name, "[[triggers]] event " + tr.event);
  return out;
}

std::unique_ptr<fit::ResidualProblem> OdeScenario::make_fit(const fit::FitSpec& spec) const {
  if (!spec.conditions.empty())
    return std::make_unique<fit::ConditionsProblem>(*model_, spec.parameters, spec.targets, spec.problem, spec.conditions);
  return std::make_unique<fit::FitProblem>(*model_, spec.parameters, spec.targets, spec.problem);
}

}  // namespace phasmid::scenario
