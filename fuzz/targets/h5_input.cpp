// Fuzz target: the HDF5 input readers, on the input written to a file: what `report` extracts
// (report::extract, every panel), what `features` and `sweep` print (the /features and
// /sweep/ranges readers) and a shard as `merge` reads it (merged into a scratch output).
#include "fuzz_input.hpp"
#include "h5_readers.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  phasmid::fuzz::read_h5_as_phasmid_does(phasmid::fuzz::write_scratch("input.h5", data, size));
  return 0;
}
