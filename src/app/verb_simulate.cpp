// phasmid simulate CONFIG [-o OUT.h5] [--set NAME=VALUE ...]
#include <iostream>

#include "app/verb.hpp"
#include "config/config.hpp"
#include "features/features.hpp"
#include "io/trajectory_writer.hpp"
#include "solver/simulator.hpp"

namespace phasmid::app {
namespace {
struct SimulateArgs {
  std::string config, out;
  std::vector<std::string> sets;
  bool quiet = false;
};

// One line per triggered command time (its value is needed to reproduce the run with fixed
// times, e.g. for `phasmid sensitivity`), and one per trigger that never fired.
// "front.touchdown" or, with in_stance, "front.touchdown with hind in stance".
std::string trigger_text(const model::CommandTrigger& tr) {
  std::string s = tr.event;
  for (size_t i = 0; i < tr.in_stance.size(); ++i)
    s += (i == 0 ? " with " : i + 1 == tr.in_stance.size() ? " and " : ", ") + tr.in_stance[i].leg;
  return tr.in_stance.empty() ? s : s + " in stance";
}

void report_triggers(const model::OdeModel& m, const solver::SolveResult& r) {
  const auto& triggers = m.triggers();
  std::vector<bool> fired(triggers.size(), false);
  for (const auto& c : r.commands) {
    fired[c.trigger] = true;
    std::cerr << "phasmid simulate: " << m.parameters().at(c.parameter).name << " = " << c.t_ms << " ms (trigger "
              << trigger_text(triggers[c.trigger]) << ")\n";
  }
  for (size_t k = 0; k < triggers.size(); ++k)
    if (!fired[k])
      std::cerr << "phasmid simulate: warning: trigger " << trigger_text(triggers[k]) << " for "
                << m.parameters().at(triggers[k].targets.front()).name << " did not fire before the end of the run\n";
}

int run_simulate(const SimulateArgs& a) {
  config::Config cfg = config::load_config(a.config);
  auto model = config::build_model(cfg, a.sets);
  config::SimulationSettings s = config::simulation_settings(cfg);
  s.solver.progress = !a.quiet;
  std::vector<double> p = model->parameters().values();
  solver::Simulator sim(*model, s.solver);
  solver::SolveResult r = sim.run(p, solver::output_grid(s.t_end_ms, s.output_dt_ms), features::feature_roots(*model));
  features::FeatureOptions fo;
  fo.discard_ms = s.discard_ms;
  std::vector<features::Feature> feats = features::compute_features(*model, r, fo);

  std::string out = a.out.empty() ? "simulation.h5" : a.out;
  io::H5Writer w(out);
  w.write_run_info({config::resolved_config_text(cfg, a.sets), command_line()});
  io::write_trajectory(w, *model, r);
  // Command times resolved by [[triggers]] are recorded with the values they took in the run.
  for (const auto& c : r.commands) p[c.parameter] = c.t_ms;
  io::write_parameters(w, *model, p);
  features::write_features_h5(w, feats);
  w.commit();
  if (!a.quiet) report_triggers(*model, r);
  if (!a.quiet)
    std::cerr << "phasmid simulate: " << model->num_states() << " states, " << s.t_end_ms << " ms in "
              << r.stats.wall_seconds << " s"
              << (r.stats.integrators > 1 ? " (" + std::to_string(r.stats.integrators) + " joint integrators)" : "")
              << " -> " << out << "\n";
  return 0;
}

const RegisterVerb reg{{"simulate", "Integrate a scenario and write its trajectory to HDF5",
                        [](CLI::App& sub) {
                          auto a = std::make_shared<SimulateArgs>();
                          sub.add_option("config", a->config, "scenario config (TOML)")->required();
                          sub.add_option("-o,--output", a->out, "output HDF5 file (default simulation.h5)");
                          sub.add_option("--set", a->sets, "override a parameter: NAME=VALUE (repeatable)");
                          sub.add_flag("-q,--quiet", a->quiet, "no progress output");
                          return std::function<int()>([a] { return run_simulate(*a); });
                        }}};
}  // namespace
}  // namespace phasmid::app
