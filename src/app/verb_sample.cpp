// phasmid sample CONFIG [--data KIN] [--parameters PARAMS.tsv] [--chains N] [--draws N]
//                       [--seed S] [--start prior|fit] [-o OUT.h5]   (docs/sampling.md)
// Exit status: 0 the chains pass the diagnostics, 3 written with warnings (R-hat, ESS,
// burn-in; one line each), 1 bad input (one line on stderr).
#include <iostream>

#include "app/options.hpp"
#include "common/error.hpp"
#include "app/verb.hpp"
#include "app/write_output.hpp"
#include "config/config.hpp"
#include "config/fit_section.hpp"
#include "config/sample_section.hpp"
#include "io/h5_file.hpp"
#include "io/output_path.hpp"
#include "parallel/session.hpp"
#include "sample/sample_run.hpp"

namespace phasmid::app {
namespace {
struct SampleArgs {
  std::string config, out = "sample.h5";
  std::vector<std::string> sets;
  fit::FitOverrides fit;
  config::SampleOverrides sample;
  bool quiet = false;
};

int run_sample_verb(const SampleArgs& a) {
  if (parallel::size() > 1) throw Error("phasmid sample runs in one process (its chains on threads, -j); not under mpirun yet");
  io::check_output_path(a.out, {a.config, a.fit.data, a.fit.parameters});
  const auto lock = lock_output(a.out, true);
  config::Config cfg = config::load_config(a.config);
  auto scenario = config::build_scenario(cfg, a.sets);
  fit::FitSpec fit_spec = config::fit_spec(cfg, *scenario, a.fit);
  config::SampleOverrides ov = a.sample;
  ov.threads = a.fit.threads;
  sample::SampleSpec spec = config::sample_spec(cfg, ov);
  auto problem = scenario->make_fit(fit_spec);
  sample::check_sampling_problem(*problem, fit_spec);
  spec.progress = !a.quiet;
  fit_spec.optimizer.progress = !a.quiet;
  std::vector<std::string> inputs = fit_spec.inputs;
  inputs.push_back(a.config);
  io::check_output_path(a.out, inputs);
  io::H5Writer w(a.out);
  const sample::SampleResult result = sample::run_sampling(*problem, fit_spec, spec);
  write_run_file(w, cfg, a.sets, *scenario);
  sample::write_sample_h5(w, *problem, spec, result);
  w.commit();
  if (!a.quiet) std::cerr << sample::format_result(*problem, spec, result) << "phasmid sample: -> " << a.out << "\n";
  return result.warnings.empty() ? 0 : 3;
}

const RegisterVerb reg{{"sample", "Sample the posterior of a fit's parameters (adaptive Metropolis, parallel tempering)",
                        [](CLI::App& sub) {
                          auto a = std::make_shared<SampleArgs>();
                          add_config_arg(sub, a->config, "scenario config (TOML) with [fit] and optionally [sample]");
                          sub.add_option("--data", a->fit.data, "kinematic recording (as for phasmid fit)");
                          sub.add_option("--data-format", a->fit.data_format, "csv (default) or anipose");
                          sub.add_option("--parameters", a->fit.parameters, "PEtab parameter table (TSV), with priors");
                          sub.add_option("--target-set", a->fit.target_set, "which set of [[fit.feature]]/[[fit.switch]] targets");
                          add_long(sub, "--chains", a->sample.chains, "independent chains");
                          add_long(sub, "--draws", a->sample.draws, "steps per chain, burn-in included");
                          add_long(sub, "--seed", a->sample.seed, "seed of the chains' random streams");
                          sub.add_option("--start", a->sample.start, "prior (default) or fit");
                          add_output(sub, a->out, "sample.h5");
                          add_sets(sub, a->sets);
                          add_threads(sub, a->fit.threads);
                          add_quiet(sub, a->quiet);
                          return std::function<int()>([a] { return run_sample_verb(*a); });
                        }}};
}  // namespace
}  // namespace phasmid::app
