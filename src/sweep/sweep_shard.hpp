#pragma once
// Sweeps split into shards for job arrays without MPI (docs/cluster.md):
// `phasmid sweep CONFIG --shard i/N -o part_i.h5` computes the points whose index is i modulo N
// and writes a shard file; `phasmid merge part_*.h5 -o OUT.h5` joins the shards into the file
// the whole sweep writes, with the same datasets bit for bit.
//
// A shard file holds the root run attributes and /sweep_shard: the journal lines of its points
// (exact: hex floats, checksums) in point order, the config text and --set overrides the sweep
// was run with (merge rebuilds the design and the base parameters from them), and the sweep's
// fingerprint, so shards of different configs are refused.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "io/h5_file.hpp"
#include "sweep/sweep_spec.hpp"

namespace phasmid::sweep {

struct SweepInputs;

struct Shard {
  std::size_t index = 0, count = 0;  // count 0: the whole sweep
  bool active() const { return count > 0; }
  bool owns(std::size_t point) const { return count == 0 || point % count == index; }
};

// "i/N" with 0 <= i < N; throws Error naming the text otherwise.
Shard parse_shard(const std::string& text);
// The journal fingerprint of a shard: a journal of shard 1/4 does not resume shard 2/4.
std::uint64_t shard_fingerprint(std::uint64_t sweep_fingerprint, const Shard& shard);

void write_shard_h5(const std::string& output, const SweepInputs& in, const Shard& shard,
                    const std::vector<std::string>& records, const io::RunInfo& info);

struct MergeOutcome {
  std::size_t n_points = 0, n_failed = 0, n_shards = 0;
};
// The sweep the shards ran, rebuilt from the config text, its origin and the --set overrides
// a shard keeps (the config layer's sweep_inputs over the parsed text; `phasmid merge`).
using InputsFromConfig = std::function<SweepInputs(const std::string& config_text, const std::string& config_path,
                                                   const std::vector<std::string>& sets)>;
// Refuses (Error, nothing written) shards of different sweeps or shard counts, duplicate
// shards, and an incomplete set, naming the missing points and shards.
MergeOutcome merge_shards(const std::vector<std::string>& parts, const std::string& output, const std::string& command,
                          const InputsFromConfig& inputs_of);

}  // namespace phasmid::sweep
