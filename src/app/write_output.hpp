#pragma once
// What every verb does the same way around its output: the output's lock, features as JSON, the
// line of an unfinished sweep. The root attributes of output files, which the Python module
// writes too, are output/run_file.hpp's.
#include <memory>
#include <string>
#include <vector>

#include "features/features.hpp"
#include "io/h5_file.hpp"
#include "io/output_lock.hpp"
#include "output/run_file.hpp"
#include "sweep/sweep_runner.hpp"

namespace phasmid::app {

// The output's lock (io/output_lock.hpp), taken right after the output-path check and before
// anything touches OUT, its .tmp, journal or .partial; the writers use it and it is held until
// the verb returns. Null on MPI worker ranks, which write nothing. With `release_workers`, a
// refusal on rank 0 also ends the workers' wait (verbs whose workers always enter the executor:
// sweep, fit), so that the job ends with the one line instead of MPI_Abort.
std::unique_ptr<io::OutputLock> lock_output(const std::string& out, bool release_workers = false);

// The root attributes of output files (output/run_file.hpp).
using output::write_run_file;
// A JSON list of {name, value, unit} on stdout (null for values that are not finite).
void print_features_json(const std::vector<features::Feature>& features);
// For a sweep that did not finish (signal or --stop-after): one line on stderr saying how much
// is done, where it is kept and the command that continues it (`resume_command` + " --resume");
// returns the exit status (128 + signal, or 3).
int report_unfinished_sweep(const std::string& verb, const sweep::SweepOutcome& r, const std::string& what,
                            const std::string& resume_command);

}  // namespace phasmid::app
