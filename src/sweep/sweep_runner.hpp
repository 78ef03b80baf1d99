#pragma once
// Runs a parameter sweep (docs/sweep.md): every point of the [sweep] design is simulated and
// reduced to gait features and a gait class, in parallel with OpenMP threads or, under mpirun,
// over MPI ranks (src/parallel: rank 0 keeps the journal and writes the file). Each point is computed
// independently from the same inputs and stored by its index, so the result does not depend
// on the number of threads or on how often the sweep was interrupted and resumed.
#include <cstddef>
#include <string>
#include <vector>

#include <functional>
#include <memory>

#include "scenario/scenario.hpp"

#include "parallel/executor.hpp"
#include "sweep/sweep_shard.hpp"
#include "sweep/sweep_store.hpp"

namespace phasmid::sweep {

struct SweepOptions {
  std::string output = "sweep.h5";
  bool resume = false;            // continue from "<output>.journal"
  int threads = 0;                // 0: OpenMP's default (OMP_NUM_THREADS or the number of cores);
                                  // under MPI per worker rank, default OMP_NUM_THREADS or 1
  Shard shard;                    // --shard i/N: only every N-th point, written as a shard file
  long stop_after = -1;           // testing: stop (as if interrupted) after this many new points
  bool progress = true;           // progress bar on a terminal
  bool handle_signals = false;    // SIGINT/SIGTERM finish the running points, then stop resumably
  std::string command;            // for the `command` attribute
  // Where the complete sweep is written ("" = output), and whether the journal outlives the
  // run: `phasmid gsa` writes its sweep apart and keeps the journal (and its lock) until /gsa
  // is in the final file, so that no file named OUT ever lacks /gsa.
  std::string sweep_file;
  bool keep_journal = false;
};

struct SweepOutcome {
  std::size_t n_points = 0;     // of the sweep, or of the shard
  std::size_t n_recovered = 0;  // taken from the journal (--resume)
  std::size_t n_computed = 0;   // computed in this run
  std::size_t n_failed = 0;     // of all points finished so far
  bool complete = false;        // false: stopped early; the journal holds the finished points
  int signal = 0;               // the signal that stopped the sweep, if any
  int threads = 0;               // evaluation threads of this process (per worker rank under MPI)
  std::string executor;          // "2 threads", "3 ranks: 2 workers x 1 thread"
  std::vector<parallel::WorkerStats> work;  // per thread or worker rank: points computed, busy time
  bool distributed = false;      // ran over MPI ranks
  bool worker = false;           // this rank was an MPI worker: nothing written, nothing to report
  double wall_seconds = 0;
  std::string output, journal;
  std::shared_ptr<Journal> kept_journal;  // with keep_journal: still open and locked
};

// What a sweep runs: the design, a factory of the scenario of each option combination
// (spec.options; called serially, once per combination and thread), how to run each point,
// the resolved config text (the file's `config` attribute) and the resume spec
// (config/resume_spec.hpp: the journal's fingerprint and the file's /sweep `resume_spec`).
struct SweepInputs {
  SweepSpec spec;
  std::function<std::unique_ptr<scenario::Scenario>(std::size_t combo)> make;
  scenario::RunSettings settings;
  std::string resolved_config;
  std::string resume_spec;
  // The config as read and the --set overrides: a shard file keeps them for `phasmid merge`.
  std::string config_text, config_path;
  std::vector<std::string> sets;
};

SweepOutcome run_sweep(const SweepInputs& inputs, const SweepOptions& options);

// One point: the base parameters with the swept ones replaced, simulated and reduced to
// features. Never throws for a failing point: the reason goes into PointResult::status.
PointResult evaluate_point(const scenario::Scenario& scenario, const std::vector<double>& base_parameters,
                           const std::vector<std::size_t>& swept_indices, const SweepSpec& spec,
                           std::size_t point, const scenario::RunSettings& settings);

// Gait class of a point from its features: the label of a `gait_class` feature if the model
// provides one (see docs/sweep.md), else "ok".
std::string gait_class_of(const std::vector<features::Feature>& features);

}  // namespace phasmid::sweep
