#pragma once
// What every verb writes the same way: the root attributes of an output file (the resolved
// config, the command line, the model kind) and features as JSON.
#include <memory>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "features/features.hpp"
#include "io/h5_file.hpp"
#include "io/output_lock.hpp"
#include "sweep/sweep_runner.hpp"

namespace phasmid::app {

// The output's lock (io/output_lock.hpp), taken right after the output-path check and before
// anything touches OUT, its .tmp, journal or .partial; the writers use it and it is held until
// the verb returns. Null on MPI worker ranks, which write nothing. With `release_workers`, a
// refusal on rank 0 also ends the workers' wait (verbs whose workers always enter the executor:
// sweep, fit), so that the job ends with the one line instead of MPI_Abort.
std::unique_ptr<io::OutputLock> lock_output(const std::string& out, bool release_workers = false);

// Root attributes phasmid_version, created, config (with the --set overrides), command, model.
void write_run_file(io::H5Writer& w, const config::Config& cfg, const std::vector<std::string>& sets,
                    const scenario::Scenario& scenario);
// A JSON list of {name, value, unit} on stdout (null for values that are not finite).
void print_features_json(const std::vector<features::Feature>& features);
// For a sweep that did not finish (signal or --stop-after): one line on stderr saying how much
// is done, where it is kept and the command that continues it (`resume_command` + " --resume");
// returns the exit status (128 + signal, or 3).
int report_unfinished_sweep(const std::string& verb, const sweep::SweepOutcome& r, const std::string& what,
                            const std::string& resume_command);

}  // namespace phasmid::app
