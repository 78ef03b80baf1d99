// [mpirun -np N] phasmid sweep CONFIG [-o OUT.h5] [--resume] [--shard i/N] [--set NAME=VALUE ...] [-j THREADS] [-q]
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "app/options.hpp"
#include "app/verb.hpp"
#include "app/write_output.hpp"
#include "config/sweep_inputs.hpp"
#include "parallel/executor.hpp"
#include "io/h5_file.hpp"
#include "io/output_path.hpp"
#include "sweep/sweep_store.hpp"
#include "sweep/ranges.hpp"
#include "sweep/sweep_runner.hpp"

namespace phasmid::app {
namespace {
struct SweepArgs {
  std::string config, out = "sweep.h5";
  std::vector<std::string> sets;
  std::string shard;
  bool resume = false, quiet = false, json = false;
  int threads = 0;
  long stop_after = -1;
};

// The range analysis of a one-at-a-time sweep, read back from the file it was written to.
void print_ranges(const std::string& path, bool json) {
  io::H5Reader in(path);
  const auto ranges = sweep::read_ranges_h5(in);
  if (ranges.empty()) return;
  if (json) {
    nlohmann::json j = nlohmann::json::array();
    auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
    for (const auto& r : ranges)
      j.push_back({{"parameter", r.parameter}, {"lower", num(r.lower)}, {"upper", num(r.upper)},
                   {"contiguous", r.contiguous}, {"values", r.values}, {"in_range", r.in_range}});
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::cout << "range of " << in.read_string_attribute("/sweep/ranges", "feature") << " = 1:\n"
            << fmt::format("{:<24} {:>10} {:>10}  {}\n", "parameter", "lower", "upper", "contiguous");
  for (const auto& r : ranges)
    std::cout << fmt::format("{:<24} {:>10.4g} {:>10.4g}  {}\n", r.parameter, r.lower, r.upper, r.contiguous ? "yes" : "no");
}

int run(const SweepArgs& a) {
  io::check_output_path(a.out, {a.config}, {sweep::Journal::path_for(a.out)});
  const auto lock = lock_output(a.out, true);  // rank 0 only, before the journal is opened
  config::Config cfg = config::load_config(a.config);
  sweep::SweepOptions o;
  o.output = a.out;
  o.resume = a.resume;
  o.threads = a.threads;
  o.stop_after = a.stop_after;
  if (!a.shard.empty()) o.shard = sweep::parse_shard(a.shard);
  o.progress = !a.quiet;
  o.handle_signals = true;
  o.command = command_line();
  sweep::SweepOutcome r = sweep::run_sweep(config::sweep_inputs(cfg, a.sets), o);
  if (r.worker) return 0;  // MPI worker rank: rank 0 reports
  if (!r.complete)
    return report_unfinished_sweep("sweep", r, "points",
                                   "phasmid sweep " + a.config + " -o " + a.out + (a.shard.empty() ? "" : " --shard " + a.shard));
  if (a.shard.empty()) print_ranges(r.output, a.json);
  if (!a.quiet)
    std::cerr << "phasmid sweep: " << r.n_points << " points" << (a.shard.empty() ? "" : " of shard " + a.shard) << " (" << r.n_failed << " failed, " << r.n_recovered
              << " resumed) on " << r.executor << " in " << r.wall_seconds << " s -> " << r.output << "\n";
  if (!a.quiet && r.distributed) std::cerr << "phasmid sweep: work per rank\n" << parallel::format_work_summary(r.work, "points");
  return 0;
}

const RegisterVerb reg{{"sweep", "Run every point of a parameter sweep ([sweep] section) and write features to HDF5",
                        [](CLI::App& sub) {
                          auto a = std::make_shared<SweepArgs>();
                          add_config_arg(sub, a->config, "scenario config (TOML) with a [sweep] section");
                          add_output(sub, a->out, "sweep.h5");
                          sub.add_flag("--resume", a->resume, "continue an interrupted sweep from OUT.h5.journal");
                          sub.add_option("--shard", a->shard,
                                         "i/N: only points with index i modulo N, written as a shard for `phasmid merge`");
                          add_sets(sub, a->sets);
                          add_threads(sub, a->threads);
                          sub.add_option("--stop-after", a->stop_after,
                                         "testing: stop as if interrupted after computing K points")
                              ->check(CLI::Range(0, 10000000));  // at most the sweep's points; says the limit
                          add_quiet(sub, a->quiet);
                          add_json(sub, a->json);
                          return std::function<int()>([a] { return run(*a); });
                        }}};
}  // namespace
}  // namespace phasmid::app
