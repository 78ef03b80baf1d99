#pragma once
// The root attributes every output file gets, written the same way by the command-line verbs
// and the Python module (both link this library): the resolved config, the command, the model
// kind.
#include <string>
#include <vector>

#include "config/config.hpp"
#include "io/h5_file.hpp"

namespace phasmid::output {

// The `command` attribute of the files this process writes: the command line as typed
// (set once by the CLI's main) or the Python module's name and version (set when it loads).
void set_command_line(std::string text);
const std::string& command_line();

// Root attributes phasmid_version, created, config (with the --set overrides), command, model.
void write_run_file(io::H5Writer& w, const config::Config& cfg, const std::vector<std::string>& sets,
                    const scenario::Scenario& scenario);

}  // namespace phasmid::output
