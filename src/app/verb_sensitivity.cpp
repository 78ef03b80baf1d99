// phasmid sensitivity CONFIG [-o OUT.h5] [--method forward|fd] [--set NAME=VALUE ...]
#include <iostream>

#include "app/verb.hpp"
#include "common/error.hpp"
#include "config/config.hpp"
#include "sensitivity/job.hpp"

namespace phasmid::app {
namespace {
struct SensitivityArgs {
  std::string config, out, method;
  std::vector<std::string> sets;
};

int run_sensitivity(const SensitivityArgs& a) {
  config::Config cfg = config::load_config(a.config);
  auto model = config::build_model(cfg, a.sets);
  const toml::table* section = cfg.table["sensitivity"].as_table();
  if (!section) throw Error(cfg.path + ": no [sensitivity] section (it lists the parameters to differentiate by)");
  // Defaults from [simulation], overridden by [sensitivity].
  config::SimulationSettings sim = config::simulation_settings(cfg);
  sensitivity::SensitivityJob defaults;
  defaults.options.t_end_ms = sim.t_end_ms;
  defaults.options.output_dt_ms = sim.output_dt_ms;
  defaults.options.discard_ms = sim.discard_ms;
  defaults.options.solver = sim.solver;
  auto job = sensitivity::parse_sensitivity_section(*section, *model, cfg.path, defaults);
  if (!a.method.empty()) job.options.method = sensitivity::parse_method(a.method);
  job.options.solver.progress = true;
  job.options.solver.progress_label = "sensitivity";
  std::vector<double> p = model->parameters().values();
  auto outcome = sensitivity::run_sensitivity_job(*model, p, job);
  std::string out = a.out.empty() ? "sensitivity.h5" : a.out;
  sensitivity::write_sensitivity_file(out, *model, p, job, outcome,
                                      {config::resolved_config_text(cfg, a.sets), command_line()});
  std::cout << sensitivity::format_summary(outcome);
  std::cerr << "phasmid sensitivity: wrote " << out << "\n";
  return 0;
}

const RegisterVerb reg{{"sensitivity", "Forward sensitivities of trajectory and gait features (CVODES)",
                        [](CLI::App& sub) {
                          auto a = std::make_shared<SensitivityArgs>();
                          sub.add_option("config", a->config, "scenario config with a [sensitivity] section")->required();
                          sub.add_option("-o,--output", a->out, "output HDF5 file (default sensitivity.h5)");
                          sub.add_option("--method", a->method, "forward (CVODES, default) or fd (central differences)");
                          sub.add_option("--set", a->sets, "override a parameter: NAME=VALUE");
                          return std::function<int()>([a] { return run_sensitivity(*a); });
                        }}};
}  // namespace
}  // namespace phasmid::app
