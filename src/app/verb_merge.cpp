// phasmid merge PART.h5... -o OUT.h5: join the shards of `phasmid sweep --shard i/N` into the
// file the whole sweep writes (docs/cluster.md).
#include <iostream>

#include "app/verb.hpp"
#include "app/write_output.hpp"
#include "config/sweep_inputs.hpp"
#include "io/output_path.hpp"
#include "sweep/sweep_shard.hpp"

namespace phasmid::app {
namespace {
struct MergeArgs {
  std::vector<std::string> parts;
  std::string out = "sweep.h5";
  bool quiet = false;
};

int run(const MergeArgs& a) {
  io::check_output_path(a.out, a.parts);
  const auto lock = lock_output(a.out);
  const auto inputs_of = [](const std::string& text, const std::string& path, const std::vector<std::string>& sets) {
    return config::sweep_inputs(config::parse_config(text, path), sets);
  };
  sweep::MergeOutcome r = sweep::merge_shards(a.parts, a.out, command_line(), inputs_of);
  if (!a.quiet)
    std::cerr << "phasmid merge: " << r.n_shards << " shards, " << r.n_points << " points (" << r.n_failed
              << " failed) -> " << a.out << "\n";
  return 0;
}

const RegisterVerb reg{{"merge", "Join the shard files of `phasmid sweep --shard i/N` into one sweep file",
                        [](CLI::App& sub) {
                          auto a = std::make_shared<MergeArgs>();
                          sub.add_option("shards", a->parts, "shard files (every shard of one sweep)")->required();
                          sub.add_option("-o,--output", a->out, "output HDF5 file (default sweep.h5)");
                          sub.add_flag("-q,--quiet", a->quiet, "no summary");
                          return std::function<int()>([a] { return run(*a); });
                        }}};
}  // namespace
}  // namespace phasmid::app
