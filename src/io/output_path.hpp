#pragma once
// The one check every file phasmid writes goes through (docs/reliability.md): an output path
// must be new or an existing regular file (not /dev/null, a directory, a fifo, a socket or a
// symlink to one of them), and must not be the same file as any input of the run (compared
// by device and inode, so "./a.h5", "a.h5" and a hard link are one file). The temporary
// companions "<out>.tmp" (and the caller's others, e.g. the sweep journal) are checked the
// same way. io::H5Writer and the report writer call it themselves for the kind checks; every
// verb that writes calls it with its inputs before any work, and a new verb must too:
// simulate, fit, sweep, sensitivity, report, merge, demo (its directory), gsa, continue.
// Right after it, a verb locks the output (io/output_lock.hpp) before touching any file of it.
#include <string>
#include <vector>

namespace phasmid::io {

// Throws phasmid::Error "<what> <path>: <reason>" (one line) if `out` or any of `companions`
// may not be written; inputs that do not exist on disk (embedded configs) are skipped.
void check_output_path(const std::string& out, const std::vector<std::string>& inputs = {},
                       const std::vector<std::string>& companions = {});

// The same for a directory the run writes into (demo): new, or an existing directory.
void check_output_directory(const std::string& dir);

}  // namespace phasmid::io
