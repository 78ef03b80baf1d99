#include "config/cruse_section.hpp"

#include <fmt/format.h>

#include <memory>

#include "common/error.hpp"
#include "config/fit_section.hpp"
#include "cruse/cruse1980_fit.hpp"
#include "fit/parameter_table.hpp"

namespace phasmid::config {

fit::FitSpec parse_cruse_fit(const Config& cfg, const model::ParameterSet& base, const fit::FitOverrides& ov) {
  if (!ov.data.empty() || !ov.data_format.empty())
    throw Error("--data: the cruse1980 model has no kinematic channels; give [[fit.feature]] targets");
  const toml::table& fit = fit::fit_section(cfg);
  check_keys(cfg, fit, "fit",
             {"description", "optimizer", "max_evaluations", "function_tolerance", "parameter_tolerance", "multistart",
              "sampling", "seed", "threads", "absolute_sigma", "target_set", "parameter_table", "parameters", "feature",
              "start_positions", "cycles"});
  fit::FitSpec spec;
  // Default optimiser: derivative-free (the config or --optimizer may choose another NLopt method).
  spec.optimizer.method = "nlopt:BOBYQA";
  fit::load_fit_common(cfg, fit, ov, {"feature"},
                       [&](const std::string& id) {
                         for (const auto& np : base.all())
                           if (fit::parameter_id_matches(id, np.name)) return np.value;
                         return 0.0;
                       },
                       spec);
  auto kind = std::make_shared<cruse::CruseFitSpec>();
  cruse::CruseFitSettings& settings = kind->settings;
  if (auto n = fit.get("start_positions")) {
    auto a = n->as_array();
    if (!a) throw Error(where(cfg, *n) + ": start_positions must be an array of Table 2 positions (1..10)");
    settings.start_positions.clear();
    for (auto& e : *a) {
      auto v = e.value<int64_t>();
      if (!v || *v < 1 || *v > 10) throw Error(where(cfg, e) + ": start_positions entries must be integers 1..10");
      settings.start_positions.push_back(static_cast<int>(*v));
    }
  }
  if (auto n = fit.get("cycles")) settings.cycles = number(cfg, *n, "cycles");
  std::vector<cruse::CruseTarget>& targets = kind->targets;
  for (auto* t : fit::fit_tables(cfg, fit, "feature")) {
    check_keys(cfg, *t, "fit.feature", {"name", "value", "tolerance", "period_ms", "set"});
    if (!fit::in_target_set(cfg, *t, spec.target_set)) continue;
    const fit::FeatureTarget f = fit::feature_target(cfg, *t);
    cruse::CruseTarget c;
    c.feature = f.feature, c.value = f.value, c.tolerance = f.tolerance, c.origin = f.origin;
    if (auto n = t->get("period_ms")) c.period_ms = number(cfg, *n, "period_ms");
    targets.push_back(c);
    spec.targets.features.push_back(
        {c.period_ms > 0 ? fmt::format("{} @{}ms", c.feature, c.period_ms) : c.feature, c.value, c.tolerance, c.origin});
  }
  if (targets.empty()) throw Error(cfg.path + ": the fit has no targets (give [[fit.feature]] in [fit])");
  spec.optimizer.progress_label = "fit";
  spec.kind = std::move(kind);
  return spec;
}

}  // namespace phasmid::config
