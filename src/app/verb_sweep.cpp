// [mpirun -np N] phasmid sweep CONFIG [-o OUT.h5] [--resume] [--shard i/N] [--set NAME=VALUE ...] [-j THREADS]
#include <iostream>

#include "app/verb.hpp"
#include "common/error.hpp"
#include "config/config.hpp"
#include "sweep/sweep_runner.hpp"

namespace phasmid::app {
namespace {
struct SweepArgs {
  std::string config, out = "sweep.h5";
  std::vector<std::string> sets;
  std::string shard;
  bool resume = false, quiet = false;
  int threads = 0;
  long stop_after = -1;
};

int run(const SweepArgs& a) {
  config::Config cfg = config::load_config(a.config);
  sweep::SweepOptions o;
  o.output = a.out;
  o.sets = a.sets;
  o.resume = a.resume;
  o.threads = a.threads;
  o.stop_after = a.stop_after;
  if (!a.shard.empty()) o.shard = sweep::parse_shard(a.shard);
  o.progress = !a.quiet;
  o.handle_signals = true;
  o.command = command_line();
  sweep::SweepOutcome r = sweep::run_sweep(cfg, o);
  if (r.worker) return 0;  // MPI worker rank: rank 0 reports
  if (!r.complete) {
    std::cerr << "phasmid sweep: " << (r.signal ? "interrupted" : "stopped") << " with "
              << (r.n_recovered + r.n_computed) << " of " << r.n_points << " points done (kept in " << r.journal
              << "); continue with: " << (r.distributed ? "mpirun ... " : "") << "phasmid sweep " << a.config << " -o "
              << a.out << (a.shard.empty() ? "" : " --shard " + a.shard) << " --resume\n";
    return r.signal ? 128 + r.signal : 3;
  }
  if (!a.quiet)
    std::cerr << "phasmid sweep: " << r.n_points << " points" << (a.shard.empty() ? "" : " of shard " + a.shard) << " (" << r.n_failed << " failed, " << r.n_recovered
              << " resumed) on " << r.executor << " in " << r.wall_seconds << " s -> " << r.output << "\n";
  if (!a.quiet && r.distributed) std::cerr << "phasmid sweep: work per rank\n" << dist::format_work_summary(r.work, "points");
  return 0;
}

const RegisterVerb reg{{"sweep", "Simulate every point of a parameter sweep ([sweep] section) and write features to HDF5",
                        [](CLI::App& sub) {
                          auto a = std::make_shared<SweepArgs>();
                          sub.add_option("config", a->config, "scenario config (TOML) with a [sweep] section")->required();
                          sub.add_option("-o,--output", a->out, "output HDF5 file (default sweep.h5)");
                          sub.add_flag("--resume", a->resume, "continue an interrupted sweep from OUT.h5.journal");
                          sub.add_option("--shard", a->shard,
                                         "i/N: only points with index i modulo N, written as a shard for `phasmid merge`");
                          sub.add_option("--set", a->sets, "override a parameter for every point: NAME=VALUE (repeatable)");
                          sub.add_option("-j,--threads", a->threads, "worker threads (default: OMP_NUM_THREADS or all cores; under mpirun per rank, default OMP_NUM_THREADS or 1)")
                              ->check(CLI::NonNegativeNumber);
                          sub.add_option("--stop-after", a->stop_after,
                                         "testing: stop as if interrupted after computing K points")
                              ->check(CLI::NonNegativeNumber);
                          sub.add_flag("-q,--quiet", a->quiet, "no progress bar or summary");
                          return std::function<int()>([a] { return run(*a); });
                        }}};
}  // namespace
}  // namespace phasmid::app
