#include "config/gsa_inputs.hpp"

#include "common/error.hpp"
#include "config/gsa_section.hpp"
#include "config/sweep_inputs.hpp"
#include "config/sweep_section.hpp"

namespace phasmid::config {

gsa::GsaInputs gsa_inputs(const Config& cfg, const std::vector<std::string>& sets) {
  gsa::GsaInputs in;
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

}  // namespace phasmid::config
