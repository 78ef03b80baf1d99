#include "config/gsa_inputs.hpp"

#include "config/gsa_section.hpp"
#include "config/sweep_inputs.hpp"
#include "config/sweep_section.hpp"

namespace phasmid::config {

GsaInputs gsa_inputs(const Config& cfg, const std::vector<std::string>& sets) {
  GsaInputs in;
  in.sweep = sweep_inputs(cfg, sets, sweep::parse_sweep_ranges);
  in.catalogue = in.sweep.make(0)->feature_catalogue();
  in.spec = parse_gsa_section(cfg, in.catalogue);
  in.design = gsa::make_design(in.spec, in.sweep.spec.parameters);
  sweep::set_unit_points(in.sweep.spec, in.design.unit_design());
  return in;
}

gsa::GsaResult analyse_and_write(const GsaInputs& in, const std::string& path, const std::string& command) {
  gsa::GsaResult result = in.design;
  {
    io::H5Reader sweep_file(path);
    gsa::analyse_sweep_file(sweep_file, in.spec, result);
  }
  for (gsa::FeatureResult& f : result.features)  // a feature no point produced has no unit in the file
    for (const auto& info : in.catalogue)
      if (f.unit.empty() && info.name == f.name) f.unit = info.unit;
  gsa::write_gsa_file(path, path, result, {in.sweep.resolved_config, command});
  return result;
}

}  // namespace phasmid::config
