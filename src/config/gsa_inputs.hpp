#pragma once
// What `phasmid gsa` runs, read from a config (docs/gsa.md): the [gsa] settings, the design
// they give over the [[sweep.parameter]] ranges, and the sweep whose points are that design's
// rows. Shared by the verb, the tests and the benchmark, so all of them run the same path.
#include <string>
#include <vector>

#include "config/config.hpp"
#include "gsa/gsa_run.hpp"
#include "sweep/sweep_runner.hpp"

namespace phasmid::config {

struct GsaInputs {
  sweep::SweepInputs sweep;                     // spec.points = the design, in parameter units
  gsa::GsaSpec spec;                            // [gsa]
  gsa::GsaResult design;                        // method, parameters, options, design; no features yet
  std::vector<features::FeatureInfo> catalogue;  // the scenario's features (names, units)
};

// Errors name file:line ([gsa] keys, [[sweep.parameter]] ranges, unknown features).
GsaInputs gsa_inputs(const Config& cfg, const std::vector<std::string>& sets);

// Where `phasmid gsa` writes the complete sweep before its analysis: "<output>.sweep", deleted
// once <output> (with /gsa) is written.
std::string sweep_file_for(const std::string& output);

// After the sweep of `in` finished into `sweep_path`: reads its outputs, analyses every feature
// of [gsa] and writes /sweep, /parameters and /gsa to `path` (atomically; may be sweep_path).
gsa::GsaResult analyse_and_write(const GsaInputs& in, const std::string& sweep_path, const std::string& path,
                                 const std::string& command);

// One `phasmid gsa` run, the verb's and phasmid.gsa()'s: unless `sweep_done` (the finished sweep
// of this design is in o.output already: checked with sweep::check_finished_sweep), runs the
// design's sweep with `o` into sweep_file_for(o.output), keeping the journal; when that sweep
// completed on rank 0 (not a worker, not stopped), analyses it, writes o.output with /gsa
// (command o.command), and only then deletes the journal and the sweep file. A file named
// o.output therefore always has /gsa.
struct GsaOutcome {
  sweep::SweepOutcome sweep;  // default-constructed when sweep_done
  bool analysed = false;      // false: an MPI worker rank, or the sweep stopped (journal kept)
  gsa::GsaResult result;      // when analysed
};
GsaOutcome run_gsa(const GsaInputs& in, const sweep::SweepOptions& o, bool sweep_done);

// The table `phasmid gsa` prints: per feature the used and dropped counts and each parameter's
// indices with their interval half-widths.
std::string gsa_summary(const gsa::GsaResult& r);

}  // namespace phasmid::config
