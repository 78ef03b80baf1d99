#include "gsa/gsa_job.hpp"

#include <filesystem>
#include <optional>

#include "parallel/session.hpp"
#include "io/output_lock.hpp"

namespace phasmid::gsa {

std::string sweep_file_for(const std::string& output) { return output + ".sweep"; }

GsaResult analyse_and_write(const GsaInputs& in, const std::string& sweep_path, const std::string& path,
                            const std::string& command) {
  GsaResult result = in.design;
  {
    io::H5Reader sweep_file(sweep_path);
    analyse_sweep_file(sweep_file, in.spec, result);
  }
  for (FeatureResult& f : result.features)  // a feature no point produced has no unit in the file
    for (const auto& info : in.catalogue)
      if (f.unit.empty() && info.name == f.name) f.unit = info.unit;
  write_gsa_file(sweep_path, path, result, {in.sweep.resolved_config, command});
  return result;
}

GsaOutcome run_gsa(const GsaInputs& in, const sweep::SweepOptions& o, bool sweep_done) {
  GsaOutcome out;
  // Rank 0 holds the output from the sweep's journal to the analysis' rename (the verb's lock,
  // or one taken here for the Python module).
  std::optional<io::HeldOutputLock> lock;
  if (parallel::rank() == 0) lock.emplace(o.output);
  if (sweep_done) {  // --resume of a finished file: only if it is this config's sweep
    sweep::check_finished_sweep(o.output, in.sweep);
    out.result = analyse_and_write(in, o.output, o.output, o.command);
    out.analysed = true;
    return out;
  }
  sweep::SweepOptions so = o;
  so.sweep_file = sweep_file_for(o.output);
  so.keep_journal = true;
  out.sweep = sweep::run_sweep(in.sweep, so);
  if (out.sweep.worker || !out.sweep.complete) return out;
  out.result = analyse_and_write(in, so.sweep_file, o.output, o.command);
  // Only now that OUT holds /gsa: a kill before this resumes from the complete journal.
  out.sweep.kept_journal->close_and_remove();
  out.sweep.kept_journal.reset();
  std::filesystem::remove(so.sweep_file);
  out.analysed = true;
  return out;
}

}  // namespace phasmid::gsa
