#pragma once
// One `phasmid gsa` run (docs/gsa.md), the verb's, phasmid.gsa()'s, the tests' and the
// benchmark's: the sweep whose points are the [gsa] design's rows, then the analysis of the
// finished sweep file into /gsa. The inputs are parsed from a config by config/gsa_inputs.hpp.
#include <string>
#include <vector>

#include "features/features.hpp"
#include "gsa/gsa_run.hpp"
#include "sweep/sweep_runner.hpp"

namespace phasmid::gsa {

struct GsaInputs {
  sweep::SweepInputs sweep;                      // spec.points = the design, in parameter units
  GsaSpec spec;                                  // [gsa]
  GsaResult design;                              // method, parameters, options, design; no features yet
  std::vector<features::FeatureInfo> catalogue;  // the scenario's features (names, units)
};

// Where `phasmid gsa` writes the complete sweep before its analysis: "<output>.sweep", deleted
// once <output> (with /gsa) is written.
std::string sweep_file_for(const std::string& output);

// After the sweep of `in` finished into `sweep_path`: reads its outputs, analyses every feature
// of [gsa] and writes /sweep, /parameters and /gsa to `path` (atomically; may be sweep_path).
GsaResult analyse_and_write(const GsaInputs& in, const std::string& sweep_path, const std::string& path,
                            const std::string& command);

// Unless `sweep_done` (the finished sweep of this design is in o.output already: checked with
// sweep::check_finished_sweep), runs the design's sweep with `o` into sweep_file_for(o.output),
// keeping the journal; when that sweep completed on rank 0 (not a worker, not stopped),
// analyses it, writes o.output with /gsa (command o.command), and only then deletes the
// journal and the sweep file. A file named o.output therefore always has /gsa.
struct GsaOutcome {
  sweep::SweepOutcome sweep;  // default-constructed when sweep_done
  bool analysed = false;      // false: an MPI worker rank, or the sweep stopped (journal kept)
  GsaResult result;           // when analysed
};
GsaOutcome run_gsa(const GsaInputs& in, const sweep::SweepOptions& o, bool sweep_done);

}  // namespace phasmid::gsa
