// Fuzz target: the HDF5 input readers, on the input written to a file: what `report` extracts
// (report::extract, every panel), what `features` and `sweep` print (the /features and
// /sweep/ranges readers) and a shard as `merge` reads it (merged into a scratch output).
#include <cstdio>

#include "features/features.hpp"
#include "fuzz_input.hpp"
#include "io/h5_file.hpp"
#include "report/report.hpp"
#include "sweep/ranges.hpp"
#include "sweep/sweep_shard.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace phasmid;
  const std::string path = fuzz::write_scratch("input.h5", data, size);
  fuzz::attempt([&] { report::extract(path); });
  fuzz::attempt([&] {
    io::H5Reader in(path);
    features::read_features_h5(in);
    sweep::read_ranges_h5(in);
  });
  const std::string merged = fuzz::scratch_path("merged.h5");
  fuzz::attempt([&] { sweep::merge_shards({path}, merged, "fuzz"); });
  std::remove(merged.c_str());
  return 0;
}
