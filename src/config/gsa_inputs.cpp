#include "config/gsa_inputs.hpp"

#include <fmt/format.h>

#include "common/error.hpp"

#include "config/gsa_section.hpp"
#include "config/sweep_inputs.hpp"
#include "config/sweep_section.hpp"
#include "dist/session.hpp"
#include "gsa/resolution.hpp"
#include "io/output_lock.hpp"

#include <cmath>
#include <optional>
#include <filesystem>

namespace phasmid::config {

GsaInputs gsa_inputs(const Config& cfg, const std::vector<std::string>& sets) {
  GsaInputs in;
  if (!cfg.table.get("sweep"))
    throw Error(cfg.path + ": no [sweep] section: gsa varies the parameters of its [[sweep.parameter]] tables "
                "(name, lower, upper; docs/gsa.md)");
  in.sweep = sweep_inputs(cfg, sets, sweep::parse_sweep_ranges);
  in.catalogue = in.sweep.make(0)->feature_catalogue();
  in.spec = parse_gsa_section(cfg, in.catalogue);
  check_gsa_design(cfg, in.spec, in.sweep.spec.parameters.size());
  in.design = gsa::make_design(in.spec, in.sweep.spec.parameters);
  sweep::set_unit_points(in.sweep.spec, in.design.unit_design());
  return in;
}

std::string sweep_file_for(const std::string& output) { return output + ".sweep"; }

gsa::GsaResult analyse_and_write(const GsaInputs& in, const std::string& sweep_path, const std::string& path,
                                 const std::string& command) {
  gsa::GsaResult result = in.design;
  {
    io::H5Reader sweep_file(sweep_path);
    gsa::analyse_sweep_file(sweep_file, in.spec, result);
  }
  for (gsa::FeatureResult& f : result.features)  // a feature no point produced has no unit in the file
    for (const auto& info : in.catalogue)
      if (f.unit.empty() && info.name == f.name) f.unit = info.unit;
  gsa::write_gsa_file(sweep_path, path, result, {in.sweep.resolved_config, command});
  return result;
}

GsaOutcome run_gsa(const GsaInputs& in, const sweep::SweepOptions& o, bool sweep_done) {
  GsaOutcome out;
  // Rank 0 holds the output from the sweep's journal to the analysis' rename (the verb's lock,
  // or one taken here for the Python module).
  std::optional<io::HeldOutputLock> lock;
  if (dist::rank() == 0) lock.emplace(o.output);
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

namespace {
// "v ± conf" and a mark: '*' when the index is not resolved at this N (gsa/resolution.hpp).
std::string pm(double v, double conf, bool resolved = true) {
  return fmt::format("{:>8.4f} ± {:<7.4f}{}", v, conf, resolved ? ' ' : '*');
}

// The footnote under a table with unresolved indices: the rule and the size that would do.
// Second-order indices are not in the table (they are in the file), so they are counted apart.
std::string unresolved_note(const gsa::GsaResult& r, const gsa::FeatureResolution& res) {
  const bool sobol = r.method == "sobol";
  const std::size_t n = sobol ? r.saltelli.n_base : r.morris.trajectories;
  const std::size_t shown = res.n_unresolved - res.n_unresolved_s2;
  const std::string rule = sobol ? fmt::format("half-width > {:g} or outside [{:g}, {:g}]", r.resolution,
                                               -r.resolution / 2, 1 + r.resolution / 2)
                                 : fmt::format("half-width > {:g} x the largest mu*", r.resolution);
  const std::string size = sobol ? "N" : "trajectories";
  std::string s = "  *";
  if (shown) s += fmt::format(" {} {}", shown, shown == 1 ? "index" : "indices");
  if (shown && res.n_unresolved_s2) s += " and";
  if (res.n_unresolved_s2)
    s += fmt::format(" {} second-order {} (S2, in the file)", res.n_unresolved_s2, res.n_unresolved_s2 == 1 ? "index" : "indices");
  s += fmt::format(" not resolved at {} = {} ({}); ", size, n, rule);
  if (std::isnan(res.n_to_resolve)) return s + "their intervals are undefined, so no size can be estimated\n";
  return s + fmt::format("about {} = {:.0f} would resolve them (from the nested subsets' convergence)\n", size,
                         res.n_to_resolve);
}

std::string feature_table(const gsa::GsaResult& r, const gsa::FeatureResult& f) {
  const bool sobol = r.method == "sobol";
  const double level = 100 * r.bootstrap.confidence;
  const gsa::OutputCounts& c = sobol ? f.sobol.counts : f.morris.counts;
  std::string s = fmt::format("{} ({}): {} of {} {} used ({} non-finite outputs, {} dropped)\n", f.name,
                              f.unit.empty() ? "-" : f.unit, c.n_used, c.n_used + c.n_dropped,
                              sobol ? "base rows" : "trajectories", c.n_nonfinite, c.n_dropped);
  if (sobol && c.n_used >= 2 && !(f.sobol.variance > 0))
    return s + "  no variance over the A and B rows (constant there): indices undefined (NaN)\n";
  const gsa::FeatureResolution res = gsa::resolve(r, f);
  if (sobol) s += fmt::format("  {:<28} {:>20} {:>20}   ({:g} % intervals)\n", "parameter", "S1", "ST", level);
  else s += fmt::format("  {:<28} {:>20} {:>10} {:>10}   ({:g} % intervals)\n", "parameter", "mu*", "mu", "sigma", level);
  for (std::size_t j = 0; j < r.parameters.size(); ++j) {
    const std::string& name = r.parameters[j].name;
    if (sobol)
      s += fmt::format("  {:<28} {} {}\n", name, pm(f.sobol.S1[j], f.sobol.S1_conf[j], res.S1[j]),
                       pm(f.sobol.ST[j], f.sobol.ST_conf[j], res.ST[j]));
    else
      s += fmt::format("  {:<28} {} {:>10.4g} {:>10.4g}\n", name, pm(f.morris.mu_star[j], f.morris.mu_star_conf[j], res.mu_star[j]),
                       f.morris.mu[j], f.morris.sigma[j]);
  }
  if (!res.all_resolved()) s += unresolved_note(r, res);
  return s;
}
}  // namespace

std::string gsa_summary(const gsa::GsaResult& r) {
  std::string s;
  for (const gsa::FeatureResult& f : r.features) s += feature_table(r, f);
  return s;
}

}  // namespace phasmid::config
