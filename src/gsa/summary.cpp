#include "gsa/summary.hpp"

#include <fmt/format.h>

#include <cmath>

#include "gsa/resolution.hpp"

namespace phasmid::gsa {
namespace {
// "v ± conf" and a mark: '*' when the index is not resolved at this N (gsa/resolution.hpp).
std::string pm(double v, double conf, bool resolved = true) {
  return fmt::format("{:>8.4f} ± {:<7.4f}{}", v, conf, resolved ? ' ' : '*');
}

// The footnote under a table with unresolved indices: the rule and the size that would do.
// Second-order indices are not in the table (they are in the file), so they are counted apart.
std::string unresolved_note(const GsaResult& r, const FeatureResolution& res) {
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

std::string feature_table(const GsaResult& r, const FeatureResult& f) {
  const bool sobol = r.method == "sobol";
  const double level = 100 * r.bootstrap.confidence;
  const OutputCounts& c = sobol ? f.sobol.counts : f.morris.counts;
  std::string s = fmt::format("{} ({}): {} of {} {} used ({} non-finite outputs, {} dropped)\n", f.name,
                              f.unit.empty() ? "-" : f.unit, c.n_used, c.n_used + c.n_dropped,
                              sobol ? "base rows" : "trajectories", c.n_nonfinite, c.n_dropped);
  if (sobol && c.n_used >= 2 && !(f.sobol.variance > 0))
    return s + "  no variance over the A and B rows (constant there): indices undefined (NaN)\n";
  const FeatureResolution res = resolve(r, f);
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

std::string gsa_summary(const GsaResult& r) {
  std::string s;
  for (const FeatureResult& f : r.features) s += feature_table(r, f);
  return s;
}

}  // namespace phasmid::gsa
