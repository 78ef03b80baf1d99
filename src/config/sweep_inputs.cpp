#include "config/sweep_inputs.hpp"

#include "config/resume_spec.hpp"
#include "config/sweep_section.hpp"

#include "common/error.hpp"

namespace phasmid::config {

sweep::SweepInputs sweep_inputs(const Config& cfg, const std::vector<std::string>& sets) {
  return sweep_inputs(cfg, sets, sweep::parse_sweep);
}

sweep::SweepInputs sweep_inputs(const Config& cfg, const std::vector<std::string>& sets, const DesignReader& design) {
  sweep::SweepInputs in;
  std::unique_ptr<scenario::Scenario> base = build_scenario(cfg, sets);
  in.settings = simulation_settings(cfg, base.get());
  in.spec = design(cfg, base->parameters(), in.settings);
  in.resolved_config = resolved_config_text(cfg, sets);
  in.resume_spec = resume_spec(cfg, base->parameters());
  in.config_text = cfg.text;
  in.config_path = cfg.path;
  in.sets = sets;
  in.make = [cfg, sets, spec = in.spec](std::size_t combo) {
    try {
      return build_scenario(sweep::config_for(cfg, spec, combo), sets);
    } catch (const Error& e) {
      std::string at;
      for (std::size_t k = 0; k < spec.options.size(); ++k) at = spec.options[k].where[spec.option_value(combo, k)];
      throw Error(at + ": sweep option " + spec.describe_combo(combo) + ": " + e.what());
    }
  };
  return in;
}

}  // namespace phasmid::config
