#pragma once
// The resume fingerprint's text (docs/sweep.md "Interrupting and resuming"): one canonical
// "key = value" line per thing that determines a sweep's results, so that `--resume` compares
// meaning, not spelling. It holds every model parameter after [parameters] and --set (defaults
// included), and every key of [model], [simulation], [[triggers]], [sweep] (and the legacy
// [cruse1980]) as parsed: comments, blank lines, key order and number spelling (7 or 7.0) do not
// change it. Left out: [parameters] itself (its values are in the resolved parameters), `[model]
// description` (free text), [gsa] (its design is compared as the sweep's points, and its
// analysis is always recomputed from the file), and the sections of other verbs ([fit],
// [sensitivity], [continuation]). Command-line options that only choose where and how the work
// runs (-o, -q, -j, MPI ranks) are not in it: the results do not depend on them.
#include <string>

#include "config/toml_util.hpp"
#include "model/parameters.hpp"

namespace phasmid::config {

std::string resume_spec(const Config& cfg, const model::ParameterSet& resolved);

}  // namespace phasmid::config
