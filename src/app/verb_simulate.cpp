// phasmid simulate CONFIG [-o OUT.h5] [--set NAME=VALUE ...] [-q] [--json]
#include <iostream>

#include "app/options.hpp"
#include "app/verb.hpp"
#include "app/write_output.hpp"
#include "config/config.hpp"
#include "io/output_path.hpp"
#include "io/trajectory_stream.hpp"

namespace phasmid::app {
namespace {
struct SimulateArgs {
  std::string config, out = "simulation.h5";
  std::vector<std::string> sets;
  bool quiet = false, json = false;
};

int run_simulate(const SimulateArgs& a) {
  io::check_output_path(a.out, {a.config});
  const auto lock = lock_output(a.out);
  config::Config cfg = config::load_config(a.config);
  auto scenario = config::build_scenario(cfg, a.sets);
  config::SimulationSettings s = config::simulation_settings(cfg, scenario.get());
  s.solver.progress = !a.quiet;
  io::H5Writer w(a.out);  // opened before the work so an unwritable path fails early
  // ODE kinds stream their samples into the file as they are reached (memory independent of
  // t_end_ms, docs/reliability.md "Memory").
  std::unique_ptr<io::TrajectoryStream> stream;
  if (const model::OdeModel* m = scenario->ode_model()) stream = std::make_unique<io::TrajectoryStream>(w, *m);
  s.solver.output_sink = stream.get();
  auto run = scenario->run(scenario->parameters().values(), s);
  if (stream) stream->finish();
  write_run_file(w, cfg, a.sets, *scenario);
  run->write(w);
  w.commit();
  if (a.json) print_features_json(run->features());
  if (a.quiet) return 0;
  for (const std::string& line : run->notes()) std::cerr << "phasmid simulate: " << line << "\n";
  std::cerr << "phasmid simulate: " << run->summary() << " -> " << a.out << "\n";
  return 0;
}

const RegisterVerb reg{{"simulate", "Run a scenario and write its trajectory, parameters and features to HDF5",
                        [](CLI::App& sub) {
                          auto a = std::make_shared<SimulateArgs>();
                          add_config_arg(sub, a->config);
                          add_output(sub, a->out, "simulation.h5");
                          add_sets(sub, a->sets);
                          add_quiet(sub, a->quiet);
                          add_json(sub, a->json);
                          return std::function<int()>([a] { return run_simulate(*a); });
                        }}};
}  // namespace
}  // namespace phasmid::app
