#include "sweep/sweep_shard.hpp"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <optional>

#include "common/error.hpp"
#include "io/h5_scalar.hpp"
#include "sweep/sweep_runner.hpp"
#include "sweep/sweep_store.hpp"

namespace phasmid::sweep {
namespace {

constexpr double kMaxShards = 1e6;  // more shards than any cluster has ranks

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string hex64(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016" PRIx64, v);
  return buf;
}

std::string shard_name(const Shard& s) { return std::to_string(s.index) + "/" + std::to_string(s.count); }

struct ShardFile {
  std::string path, fingerprint, config_text, config_path;
  std::vector<std::string> sets, records;
  Shard shard;
};

ShardFile read_shard_file(const std::string& path) {
  io::H5Reader r(path);
  if (!r.exists("/sweep_shard"))
    throw Error(path + ": not a sweep shard (no /sweep_shard; shards are written by phasmid sweep --shard i/N)");
  ShardFile f;
  f.path = path;
  f.fingerprint = r.read_string_attribute("/sweep_shard", "fingerprint");
  f.config_path = r.read_string_attribute("/sweep_shard", "config_path");
  const double index = r.read_double_attribute("/sweep_shard", "shard");
  const double count = r.read_double_attribute("/sweep_shard", "shards");
  // Written by phasmid as i < N; read from a file, so checked before they size anything.
  if (!(count >= 1 && count <= kMaxShards && count == std::floor(count) && index >= 0 && index < count &&
        index == std::floor(index)))
    throw Error(path + ": /sweep_shard declares shard " + number(index) + " of " + number(count) +
                " (a damaged file: expected i/N with 0 <= i < N <= " + std::to_string(static_cast<long>(kMaxShards)) + ")");
  f.shard.index = static_cast<std::size_t>(index);
  f.shard.count = static_cast<std::size_t>(count);
  f.config_text = io::read_scalar_string(r, "/sweep_shard/config_text");
  if (r.exists("/sweep_shard/sets")) f.sets = r.read_strings("/sweep_shard/sets");
  if (r.exists("/sweep_shard/records")) f.records = r.read_strings("/sweep_shard/records");
  return f;
}

// Every error about a shard names its file (HDF5's own messages name only the object).
ShardFile read_shard(const std::string& path) {
  try {
    return read_shard_file(path);
  } catch (const Error& e) {
    const std::string what = e.what();
    if (what.rfind(path + ":", 0) == 0) throw;
    throw Error(path + ": " + what);
  }
}

// Every shard of one sweep, each once; returns the path given for each shard index ("" if none).
std::vector<std::string> check_shards(const std::vector<ShardFile>& shards) {
  const ShardFile& first = shards.front();
  std::vector<std::string> seen(first.shard.count);
  for (auto& s : shards) {
    if (s.fingerprint != first.fingerprint)
      throw Error(s.path + ": shard of a different sweep than " + first.path + " (config, --set or [sweep] differ)");
    if (s.shard.count != first.shard.count)
      throw Error(s.path + ": shard " + shard_name(s.shard) + ", but " + first.path + " is one of " +
                  std::to_string(first.shard.count) + " shards");
    if (!seen.at(s.shard.index).empty())
      throw Error(s.path + ": shard " + shard_name(s.shard) + " given twice (also " + seen[s.shard.index] + ")");
    seen[s.shard.index] = s.path;
  }
  return seen;
}

// The missing shards (of those that own points) and points are listed up to kListed each
// ("..., and N more"): a merge of a few shards of a million must not print a million names.
constexpr std::size_t kListed = 10;

void refuse_missing(const std::vector<std::optional<PointResult>>& results, const std::vector<std::string>& seen) {
  std::string shards, points;
  std::size_t n_missing = 0, n_shards = 0;
  for (std::size_t k = 0; k < seen.size() && k < results.size(); ++k)  // shard k >= n_points owns no point
    if (seen[k].empty() && ++n_shards <= kListed)
      shards += (shards.empty() ? "" : ", ") + std::to_string(k) + "/" + std::to_string(seen.size());
  std::size_t first = results.size();
  for (std::size_t i = 0; i < results.size(); ++i)
    if (!results[i] && ++n_missing <= kListed) {
      points += (points.empty() ? "" : ", ") + std::to_string(i);
      first = std::min(first, i);
    }
  if (n_missing == 0) return;
  const auto more = [](std::size_t n) { return n > kListed ? ", ... and " + std::to_string(n - kListed) + " more" : std::string(); };
  // Every shard given but a point missing: the shard file lacks records (damaged or edited).
  const std::string why = n_shards ? "shard" + std::string(n_shards > 1 ? "s " : " ") + shards + more(n_shards) + " not given"
                                   : seen[first % seen.size()] + " holds no record of them";
  throw Error("merge: " + std::to_string(n_missing) + " of " + std::to_string(results.size()) + " points missing (" +
              points + more(n_missing) + "): " + why);
}

// The sweep the shards ran, from the config and --set stored in `first`; an error in them
// (a damaged or edited shard) names the shard file as well as the config's line.
SweepInputs shard_inputs(const ShardFile& first, const InputsFromConfig& inputs_of) {
  try {
    return inputs_of(first.config_text, first.config_path, first.sets);
  } catch (const Error& e) {
    throw Error(first.path + ": the config stored in /sweep_shard/config_text: " + e.what());
  }
}

}  // namespace

Shard parse_shard(const std::string& text) {
  Shard s;
  unsigned long i = 0, n = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lu/%lu%c", &i, &n, &tail) != 2 || n == 0 || i >= n || text[0] == '-' ||
      static_cast<double>(n) > kMaxShards)
    throw Error("--shard '" + text + "': expected i/N with 0 <= i < N <= 1000000 (e.g. 0/4)");
  s.index = i;
  s.count = n;
  return s;
}

std::uint64_t shard_fingerprint(std::uint64_t sweep_fp, const Shard& shard) {
  return fnv1a("#shard " + shard_name(shard), sweep_fp);
}

void write_shard_h5(const std::string& output, const SweepInputs& in, const Shard& shard,
                    const std::vector<std::string>& records, const io::RunInfo& info) {
  io::H5Writer w(output);
  w.write_run_info(info);
  w.ensure_group("/sweep_shard");
  if (!records.empty()) w.write("/sweep_shard/records", records);
  w.write("/sweep_shard/config_text", std::vector<std::string>{in.config_text});
  if (!in.sets.empty()) w.write("/sweep_shard/sets", in.sets);
  w.set_attribute("/sweep_shard", "fingerprint", hex64(sweep_fingerprint(in.resume_spec, in.spec)));
  w.set_attribute("/sweep_shard", "config_path", in.config_path);
  w.set_attribute("/sweep_shard", "shard", static_cast<double>(shard.index));
  w.set_attribute("/sweep_shard", "shards", static_cast<double>(shard.count));
  w.set_attribute("/sweep_shard", "n_points", static_cast<double>(in.spec.n_points));
  w.commit();
}

MergeOutcome merge_shards(const std::vector<std::string>& parts, const std::string& output, const std::string& command,
                          const InputsFromConfig& inputs_of) {
  if (parts.empty()) throw Error("merge: no shard files given");
  std::vector<ShardFile> shards;
  for (auto& p : parts) shards.push_back(read_shard(p));
  const std::vector<std::string> seen = check_shards(shards);
  const ShardFile& first = shards.front();
  // The design and base parameters come from the config the shards ran, as in `phasmid sweep`.
  const SweepInputs in = shard_inputs(first, inputs_of);
  const SweepSpec& spec = in.spec;
  if (hex64(sweep_fingerprint(in.resume_spec, spec)) != first.fingerprint)
    throw Error(first.path + ": its config no longer gives the sweep it was run with (another phasmid version?)");
  std::vector<std::optional<PointResult>> results(spec.n_points);
  MergeOutcome out;
  for (auto& s : shards)
    for (auto& line : s.records) {
      std::size_t i = 0;
      PointResult r;
      if (!decode_record(line, i, r) || i >= spec.n_points || !s.shard.owns(i))
        throw Error(s.path + ": corrupt record in /sweep_shard/records");
      if (r.status != "ok") ++out.n_failed;
      results[i] = std::move(r);
    }
  refuse_missing(results, seen);
  std::vector<PointResult> all;
  for (auto& r : results) all.push_back(std::move(*r));
  const auto base = in.make(0);
  try {
    write_sweep_h5(output, spec, all, base->parameters(), base->parameters().values(), {in.resolved_config, command}, in.resume_spec);
  } catch (const Error& e) {  // HDF5's messages name the object; say which file it was
    const std::string what = e.what();
    if (what.find(output) != std::string::npos) throw;
    throw Error(output + ": " + what);
  }
  out.n_points = spec.n_points;
  out.n_shards = shards.size();
  return out;
}

}  // namespace phasmid::sweep
