// Refusing HDF5 files whose global heap would stop HDF5 itself.
//
// Variable-length strings (phasmid's names, the `config` and `command` attributes) live in the
// file's global heap collections. When HDF5 1.10 loads a collection it walks the objects one
// header at a time; a free-space object (index 0) whose size field is 0 does not advance the walk,
// and HDF5 loops forever on the first string read from that collection. Nothing in HDF5's API
// bounds that loop, so a damaged file would hang `report`, `features`, `merge` and Python's
// `phasmid.read`.
//
// A string is read through its descriptor (length, collection address, object index), and HDF5
// allocates and clears `length` bytes before it looks at the object: a damaged length makes a
// few-kB file take up to 4 GB.
//
// check_global_heaps(path) reads the file in bounded blocks, finds every collection ("GCOL",
// version 1) and walks it exactly as HDF5 does; then it looks for descriptors that name an
// object of one of those collections. It refuses, with one line "<path>: damaged HDF5 global
// heap at byte N (...)", a collection on which HDF5 would not terminate and a descriptor that
// declares a string longer than the file. A collection that is merely truncated or inconsistent
// is left to HDF5, which reports those as errors. Not caught: a descriptor whose address is
// damaged as well as its length (HDF5 still allocates the length before it fails on the
// address). The scan may match inside numeric data; a match is refused only if it also has the
// exact shape of the damage, which valid data does not have by chance in practice. Matches inside
// a collection are not refused: its strings' tails and object headers can take that shape (in a
// collection of more than 2048 objects with another collection at byte 2048), and no descriptor
// lies there.
#pragma once

#include <hdf5.h>

#include <string>

namespace phasmid::io {

void check_global_heaps(const std::string& path);

// Before a variable-length string dataset of n elements is read: its descriptors, read from the
// file directly (the dataset's contiguous storage; phasmid writes no other layout for strings),
// must each declare a length the file can hold. Throws "<file>: dataset <name>: damaged string
// at element k (declares L bytes in a B-byte file)", or "... is not stored contiguously".
void check_string_descriptors(hid_t file, hid_t dataset, hsize_t n, const std::string& file_path,
                              const std::string& dataset_path);

}  // namespace phasmid::io
