// phasmid fit CONFIG [--data KIN.csv] [--parameters PARAMS.tsv] [--optimizer ceres|nlopt:NAME]
//                    [--multistart N] [-o OUT.h5]   (docs/fit.md; under mpirun: docs/cluster.md)
// Exit status: 0 converged, 3 finished without convergence (result written, summary says why),
// 1 bad input (one line on stderr).
#include <iostream>

#include "app/verb.hpp"
#include "common/error.hpp"
#include "config/config.hpp"
#include "cruse/cruse1980_fit.hpp"
#include "cruse/cruse1980_output.hpp"
#include "dist/executor.hpp"
#include "dist/session.hpp"
#include "fit/fit_config.hpp"
#include "fit/fit_run.hpp"
#include "io/h5_file.hpp"

namespace phasmid::app {
namespace {
struct FitArgs {
  std::string config, out;
  std::vector<std::string> sets, profile;
  fit::FitOverrides ov;
  bool quiet = false;
};

// The fit itself, the same for every model: optimise, write /fit, print the summary.
int fit_and_report(const FitArgs& a, const fit::ResidualProblem& problem, fit::FitSpec& spec,
                   const std::string& resolved_config, const std::string& model_attribute) {
  spec.optimizer.progress = !a.quiet;
  if (!a.profile.empty()) spec.profile = a.profile;
  const std::string out = a.out.empty() ? "fit.h5" : a.out;
  if (dist::rank() != 0) {  // an MPI worker: evaluates starts and profiles for rank 0
    fit::run_fit(problem, spec);
    return 0;
  }
  io::H5Writer w(out);  // opened before the work so an unwritable path fails early
  fit::FitResult result = fit::run_fit(problem, spec);
  w.write_run_info({resolved_config, command_line()});
  if (!model_attribute.empty()) w.set_attribute("/", "model", model_attribute);
  fit::write_fit_h5(w, problem, spec, result);
  w.commit();
  const fit::FitSummary& b = result.best();
  if (!a.quiet) std::cerr << fit::format_result(problem, result) << "phasmid fit: -> " << out << "\n";
  if (!a.quiet && dist::size() > 1)
    std::cerr << "phasmid fit: starts per rank\n" << dist::format_work_summary(result.multistart.work, "starts");
  if (!b.converged) {
    std::cerr << "phasmid fit: " << (b.usable ? "did not converge" : "failed") << " (" << b.termination
              << (b.message.empty() ? "" : ": " + b.message) << "); results in " << out << "\n";
    return 3;
  }
  return 0;
}

int run_fit_verb(const FitArgs& a) {
  config::Config cfg = config::load_config(a.config);
  if (cruse::is_cruse_config(cfg)) {
    cruse::CruseFit cf = cruse::load_cruse_fit(a.config, a.sets, a.ov);
    return fit_and_report(a, *cf.problem, cf.spec, cruse::resolved_config(cf.config), "cruse1980");
  }
  auto model = config::build_model(cfg, a.sets);
  fit::FitSpec spec = fit::load_fit_spec(cfg, *model, a.ov);
  spec.problem.solver.progress = false;
  fit::FitProblem problem(*model, spec.parameters, spec.targets, spec.problem);
  return fit_and_report(a, problem, spec, config::resolved_config_text(cfg, a.sets), "");
}

const RegisterVerb reg{{"fit", "Fit parameters to feature targets, switch conditions (2.42) or kinematic recordings; cruse1980 configs: Cruse features",
                        [](CLI::App& sub) {
                          auto a = std::make_shared<FitArgs>();
                          sub.add_option("config", a->config, "scenario config (TOML) with an optional [fit] section, or a cruse1980 config with [fit]")->required();
                          sub.add_option("--data", a->ov.data, "kinematic recording (CSV: time_ms, <leg>.<joint> in deg)");
                          sub.add_option("--data-format", a->ov.data_format, "csv (default) or anipose");
                          sub.add_option("--parameters", a->ov.parameters, "PEtab parameter table (TSV)");
                          sub.add_option("--optimizer", a->ov.optimizer, "ceres (default) or nlopt:NAME (BOBYQA, COBYLA, NELDERMEAD, SBPLX, LBFGS, SLSQP, MMA, DIRECT_L, CRS2_LM, ISRES, MLSL)");
                          sub.add_option("--multistart", a->ov.multistart, "number of starts (nominal + Latin hypercube / Sobol)");
                          sub.add_option("--seed", a->ov.seed, "seed of the start sampling");
                          sub.add_option("--target-set", a->ov.target_set, "which set of [[fit.feature]]/[[fit.switch]] targets");
                          sub.add_option("--max-iterations", a->ov.max_iterations, "Ceres iteration limit");
                          sub.add_option("--profile", a->profile, "profile likelihood of this estimated parameter (repeatable)");
                          sub.add_option("-o,--output", a->out, "output HDF5 file (default fit.h5)");
                          sub.add_option("--set", a->sets, "override a parameter: NAME=VALUE (repeatable)");
                          sub.add_flag("-q,--quiet", a->quiet, "no progress or summary output");
                          return std::function<int()>([a] { return run_fit_verb(*a); });
                        }}};
}  // namespace
}  // namespace phasmid::app
