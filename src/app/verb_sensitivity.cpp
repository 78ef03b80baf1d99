// phasmid sensitivity CONFIG [-o OUT.h5] [--method forward|fd] [--set NAME=VALUE ...] [-j N] [-q] [--json]
#include <iostream>

#include "app/options.hpp"
#include "app/verb.hpp"
#include "app/write_output.hpp"
#include "common/error.hpp"
#include "config/config.hpp"
#include "io/output_path.hpp"
#include "config/sensitivity_section.hpp"
#include "continuation/sensitivity_job.hpp"

namespace phasmid::app {
namespace {
struct SensitivityArgs {
  std::string config, out = "sensitivity.h5", method;
  std::vector<std::string> sets;
  bool quiet = false, json = false;
  int threads = 0;
};

int run_sensitivity(const SensitivityArgs& a) {
  io::check_output_path(a.out, {a.config});
  const auto lock = lock_output(a.out);
  config::Config cfg = config::load_config(a.config);
  auto scenario = config::build_scenario(cfg, a.sets);
  const model::OdeModel* model = scenario->ode_model();
  if (!model)
    throw Error(cfg.path + ": model type " + scenario->kind() +
                " is not an ODE system; forward sensitivities need one (use sweep or fit with a derivative-free optimizer)");
  sensitivity::SensitivityJob job = config::sensitivity_job(cfg, *model, config::bdf_simulation_settings(cfg, scenario.get()));
  if (!a.method.empty()) job.options.method = sensitivity::parse_method(a.method);
  job.options.threads = a.threads;
  job.options.solver.progress = !a.quiet;
  job.options.solver.progress_label = "sensitivity";
  std::vector<double> p = model->parameters().values();
  auto outcome = sensitivity::run_sensitivity_job(*model, p, job, [&](const std::string& note) {
    std::cerr << "phasmid sensitivity: " << note << "\n";
  });
  sensitivity::write_sensitivity_file(a.out, *model, p, job, outcome,
                                      {config::resolved_config_text(cfg, a.sets), command_line()});
  if (a.json) print_features_json(outcome.report.features);
  else std::cout << sensitivity::format_summary(outcome);
  if (!a.quiet) std::cerr << "phasmid sensitivity: wrote " << a.out << "\n";
  return 0;
}

const RegisterVerb reg{{"sensitivity", "Compute forward sensitivities of a scenario's trajectory and gait features (CVODES)",
                        [](CLI::App& sub) {
                          auto a = std::make_shared<SensitivityArgs>();
                          add_config_arg(sub, a->config, "scenario config (TOML) with a [sensitivity] section");
                          add_output(sub, a->out, "sensitivity.h5");
                          sub.add_option("--method", a->method, "forward (CVODES, default) or fd (central differences)");
                          add_sets(sub, a->sets);
                          add_threads(sub, a->threads);
                          add_quiet(sub, a->quiet);
                          add_json(sub, a->json);
                          return std::function<int()>([a] { return run_sensitivity(*a); });
                        }}};
}  // namespace
}  // namespace phasmid::app
