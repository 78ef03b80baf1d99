// phasmid fit CONFIG [--data KIN.csv] [--parameters PARAMS.tsv] [--optimizer ceres|nlopt:NAME]
//                    [--multistart N] [-o OUT.h5]   (docs/fit.md; under mpirun: docs/cluster.md)
// Exit status: 0 converged, 3 finished without convergence (result written, summary says why),
// 1 bad input (one line on stderr).
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "app/options.hpp"
#include "app/verb.hpp"
#include "app/write_output.hpp"
#include "config/config.hpp"
#include "parallel/executor.hpp"
#include "parallel/session.hpp"
#include "config/fit_section.hpp"
#include "fit/fit_run.hpp"
#include "io/h5_file.hpp"
#include "io/output_path.hpp"

namespace phasmid::app {
namespace {
struct FitArgs {
  std::string config, out = "fit.h5";
  std::vector<std::string> sets, profile;
  fit::FitOverrides ov;
  bool quiet = false, json = false;
};

// The estimates on stdout: name, value, standard error (null where undefined), unit.
void print_estimates_json(const fit::ResidualProblem& problem, const fit::FitResult& r) {
  auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  nlohmann::json est = nlohmann::json::array();
  const auto& se = r.uncertainty.standard_error;
  for (size_t j = 0; j < problem.num_parameters(); ++j)
    est.push_back({{"name", problem.parameter_names()[j]}, {"estimate", num(r.estimate[j])},
                   {"standard_error", se.size() > static_cast<long>(j) ? num(se[j]) : nlohmann::json()},
                   {"unit", problem.parameter_unit(j)}});
  const fit::FitSummary& b = r.best();
  std::cout << nlohmann::json{{"converged", b.converged}, {"final_cost", num(b.final_cost)}, {"parameters", est}}.dump(2)
            << "\n";
}

// The same for every model kind: the kind makes the residual problem of [fit]; optimise,
// write /fit, print the summary.
int run_fit_verb(const FitArgs& a) {
  fit::check_overrides(a.ov);  // before any file is touched; the Python module's fit() calls it too
  io::check_output_path(a.out, {a.config, a.ov.data, a.ov.parameters});
  const auto lock = lock_output(a.out, true);  // rank 0 only
  config::Config cfg = config::load_config(a.config);
  auto scenario = config::build_scenario(cfg, a.sets);
  fit::FitSpec spec = config::fit_spec(cfg, *scenario, a.ov);
  auto problem = scenario->make_fit(spec);
  spec.optimizer.progress = !a.quiet;
  if (!a.profile.empty()) spec.profile = a.profile;
  if (parallel::rank() != 0) {  // an MPI worker: evaluates starts and profiles for rank 0
    fit::run_fit(*problem, spec);
    return 0;
  }
  std::vector<std::string> inputs = spec.inputs;
  inputs.push_back(a.config);
  io::check_output_path(a.out, inputs);  // the data and parameter files the config names
  io::H5Writer w(a.out);  // opened before the work so an unwritable path fails early
  fit::FitResult result = fit::run_fit(*problem, spec);
  write_run_file(w, cfg, a.sets, *scenario);
  fit::write_fit_h5(w, *problem, spec, result);
  w.commit();
  const fit::FitSummary& b = result.best();
  if (a.json) print_estimates_json(*problem, result);
  if (!a.quiet) std::cerr << fit::format_result(*problem, result) << "phasmid fit: -> " << a.out << "\n";
  if (!a.quiet && parallel::size() > 1)
    std::cerr << "phasmid fit: starts per rank\n" << parallel::format_work_summary(result.multistart.work, "starts");
  if (!b.converged) {
    std::cerr << "phasmid fit: " << (b.usable ? "did not converge" : "failed") << " (" << b.termination
              << (b.message.empty() ? "" : ": " + b.message) << "); results in " << a.out << "\n";
    return 3;
  }
  return 0;
}

const RegisterVerb reg{{"fit", "Fit parameters to feature targets, switch conditions (2.42) or kinematic recordings",
                        [](CLI::App& sub) {
                          auto a = std::make_shared<FitArgs>();
                          add_config_arg(sub, a->config, "scenario config (TOML) with a [fit] section");
                          sub.add_option("--data", a->ov.data, "kinematic recording (CSV: time_ms, <leg>.<joint> in deg)");
                          sub.add_option("--data-format", a->ov.data_format, "csv (default) or anipose");
                          sub.add_option("--parameters", a->ov.parameters, "PEtab parameter table (TSV)");
                          sub.add_option("--optimizer", a->ov.optimizer, fit::optimizer_help());
                          add_long(sub, "--multistart", a->ov.multistart, "number of starts (nominal + Latin hypercube / Sobol)");
                          add_long(sub, "--seed", a->ov.seed, "seed of the start sampling");
                          sub.add_option("--target-set", a->ov.target_set, "which set of [[fit.feature]]/[[fit.switch]] targets");
                          add_long(sub, "--max-iterations", a->ov.max_iterations, "Ceres iteration limit");
                          sub.add_option("--profile", a->profile, "profile likelihood of this estimated parameter (repeatable)");
                          add_output(sub, a->out, "fit.h5");
                          add_sets(sub, a->sets);
                          add_threads(sub, a->ov.threads);
                          add_quiet(sub, a->quiet);
                          add_json(sub, a->json);
                          return std::function<int()>([a] { return run_fit_verb(*a); });
                        }}};
}  // namespace
}  // namespace phasmid::app
