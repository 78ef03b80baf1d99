#pragma once
// The [fit] section of a scenario config (docs/fit.md), read into a fit::FitSpec. Other verbs
// ignore [fit]; `phasmid fit` ignores sections it does not use.
#include <functional>
#include <string>
#include <vector>

#include "config/config.hpp"
#include "fit/fit_spec.hpp"

namespace phasmid::fit {

// Refuses a given override outside its range (--multistart and --max-iterations >= 1, --seed
// >= 0, -j >= 0), naming the option: the one check of `phasmid fit`'s options and of the Python
// module's fit() keywords (load_fit_common calls it; callers may call it earlier, before work).
void check_overrides(const FitOverrides& overrides);

// `model` must be the model built from the same config (nominal values default to its values).
FitSpec load_fit_spec(const config::Config& cfg, const model::OdeModel& model, const FitOverrides& overrides = {});

// Pieces of the [fit] parser for model-specific parsers (config::parse_cruse_fit).
// The [fit] table (empty if absent); [[fit.KEY]] / [fit.KEY] tables; whether a target table
// belongs to the chosen target set (its `set`, default "default").
const toml::table& fit_section(const config::Config& cfg);
std::vector<const toml::table*> fit_tables(const config::Config& cfg, const toml::table& fit, const std::string& key);
bool in_target_set(const config::Config& cfg, const toml::table& t, const std::string& set);
// The name, value and tolerance of a [[fit.feature]] table (its origin: the name's file:line).
FeatureTarget feature_target(const config::Config& cfg, const toml::table& t);
// The keys every model shares: optimiser and its stop rules, multistart, absolute_sigma,
// profiles, output_dt_ms, target_set (checked against the sets named by the [[fit.KEY]]
// tables of `target_keys`) and the parameters (--parameters, parameter_table,
// [fit.parameters] whose nominal defaults to model_value(id)). The caller checks which keys
// its model allows.
using ModelValue = std::function<double(const std::string& parameter_id)>;
void load_fit_common(const config::Config& cfg, const toml::table& fit, const FitOverrides& overrides,
                     const std::vector<std::string>& target_keys, const ModelValue& model_value, FitSpec& spec);

// [[fit.recording]] tables (with their [[fit.recording.observable]]s) of the target set: each
// recording read and summarised as step cycles (docs/recordings.md). `--data` replaces the file
// of the config's one recording.
void load_recording_targets(const config::Config& cfg, const toml::table& fit, const FitOverrides& overrides, FitSpec& spec);

// Resolves a path named in a config: absolute, relative to the config's directory, or (for
// embedded configs) relative to the working directory or the source tree.
std::string resolve_path(const config::Config& cfg, const std::string& path);

}  // namespace phasmid::fit

namespace phasmid::config {

// The fit spec of the config's [fit] for `scenario` (built from the same config): an ODE
// kind's through fit::load_fit_spec, cruse1980's through parse_cruse_fit
// (config/cruse_section.hpp). A kind without a [fit] parser gets an empty spec, and its
// make_fit says why it has no fit. The scenario's make_fit takes the result.
fit::FitSpec fit_spec(const Config& cfg, const scenario::Scenario& scenario, const fit::FitOverrides& overrides);

}  // namespace phasmid::config
