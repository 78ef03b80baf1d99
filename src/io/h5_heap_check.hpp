// Refusing HDF5 files whose global heap would stop HDF5 itself.
//
// Variable-length strings (phasmid's names, the `config` and `command` attributes) live in the
// file's global heap collections. When HDF5 1.10 loads a collection it walks the objects one
// header at a time; a free-space object (index 0) whose size field is 0 does not advance the walk,
// and HDF5 loops forever on the first string read from that collection. Nothing in HDF5's API
// bounds that loop, so a damaged file would hang `report`, `features`, `merge` and Python's
// `phasmid.read`.
//
// check_global_heaps(path) reads the file in bounded blocks, finds every collection ("GCOL",
// version 1) and walks it exactly as HDF5 does. A collection on which HDF5 would not terminate
// is refused with one line, "<path>: damaged HDF5 global heap at byte N (...)". A collection
// that is merely truncated or inconsistent is left to HDF5, which reports those as errors. The
// scan may match "GCOL" inside numeric data; such a match is refused only if it also has the
// exact shape HDF5 would loop on, which valid data does not have by chance in practice.
#pragma once

#include <string>

namespace phasmid::io {

void check_global_heaps(const std::string& path);

}  // namespace phasmid::io
