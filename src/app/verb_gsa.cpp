// [mpirun -np N] phasmid gsa CONFIG [-o OUT.h5] [--resume] [--set NAME=VALUE ...] [-j THREADS] [-q]
// Global sensitivity analysis (docs/gsa.md): the [gsa] design over the [[sweep.parameter]]
// ranges runs as a sweep (threads, MPI ranks, journal and --resume as `phasmid sweep`), then
// the analysis reads the finished sweep file and adds /gsa to it.
#include <filesystem>
#include <iostream>

#include "app/options.hpp"
#include "app/verb.hpp"
#include "app/write_output.hpp"
#include "config/gsa_inputs.hpp"
#include "gsa/summary.hpp"
#include "parallel/executor.hpp"
#include "parallel/session.hpp"
#include "io/output_path.hpp"
#include "sweep/sweep_runner.hpp"

namespace phasmid::app {
namespace {
struct GsaArgs {
  std::string config, out = "gsa.h5";
  std::vector<std::string> sets;
  bool resume = false, quiet = false;
  int threads = 0;
  long stop_after = -1;
};

// A finished sweep of this analysis is in OUT already (the run stopped before or during the
// analysis step, or the analysis is repeated): --resume then only analyses.
bool sweep_already_done(const GsaArgs& a) {
  namespace fs = std::filesystem;
  if (!a.resume || fs::exists(sweep::Journal::path_for(a.out)) || !fs::exists(a.out)) return false;
  return io::H5Reader(a.out).exists("/sweep/points");
}

int run(const GsaArgs& a) {
  io::check_output_path(a.out, {a.config},
                        {sweep::Journal::path_for(a.out), gsa::sweep_file_for(a.out), gsa::sweep_file_for(a.out) + ".tmp"});
  // Rank 0, before OUT is read or its journal opened, held through the analysis step.
  const auto lock = lock_output(a.out);
  const gsa::GsaInputs in = config::gsa_inputs(config::load_config(a.config), a.sets);
  const bool sweep_done = sweep_already_done(a);
  if (sweep_done && parallel::rank() != 0) return 0;  // MPI worker rank: rank 0 analyses
  sweep::SweepOptions o;
  o.output = a.out, o.resume = a.resume, o.threads = a.threads, o.stop_after = a.stop_after;
  o.progress = !a.quiet, o.handle_signals = true, o.command = command_line();
  const gsa::GsaOutcome r = gsa::run_gsa(in, o, sweep_done);
  const sweep::SweepOutcome& s = r.sweep;
  if (!sweep_done && s.worker) return 0;
  if (!r.analysed) return report_unfinished_sweep("gsa", s, "design points", "phasmid gsa " + a.config + " -o " + a.out);
  if (a.quiet) return 0;
  if (!sweep_done)
    std::cerr << "phasmid gsa: " << s.n_points << " design points (" << s.n_failed << " failed, " << s.n_recovered
              << " resumed) on " << s.executor << " in " << s.wall_seconds << " s\n";
  std::cout << gsa::gsa_summary(r.result);
  std::cerr << "phasmid gsa: " << r.result.method << " analysis of " << r.result.features.size() << " features -> " << a.out << "\n";
  return 0;
}

const RegisterVerb reg{{"gsa", "Run a global sensitivity analysis ([gsa] section): Sobol' indices or Morris screening, on the sweep engine",
                        [](CLI::App& sub) {
                          auto a = std::make_shared<GsaArgs>();
                          add_config_arg(sub, a->config, "scenario config (TOML) with [gsa] and [[sweep.parameter]] ranges");
                          add_output(sub, a->out, "gsa.h5");
                          sub.add_flag("--resume", a->resume,
                                       "continue an interrupted analysis from OUT.h5.journal (or re-analyse a finished OUT.h5)");
                          add_sets(sub, a->sets);
                          add_threads(sub, a->threads);
                          sub.add_option("--stop-after", a->stop_after,
                                         "testing: stop as if interrupted after computing K design points")
                              ->check(CLI::Range(0, 10000000));  // at most the sweep's points; says the limit
                          add_quiet(sub, a->quiet);
                          return std::function<int()>([a] { return run(*a); });
                        }}};
}  // namespace
}  // namespace phasmid::app
