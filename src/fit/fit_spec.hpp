#pragma once
// What a fit does (docs/fit.md): the estimated parameters, targets, optimiser, multistart and
// profiles (FitSpec), and the command-line overrides of `phasmid fit` (FitOverrides).
// config/fit_section.hpp reads them from a config's [fit] section; a scenario's make_fit takes
// the FitSpec so read and never sees the config.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fit/condition_problem.hpp"
#include "fit/fit_problem.hpp"
#include "fit/multistart.hpp"
#include "fit/optimizer.hpp"

namespace phasmid::fit {

// What a model kind's own [fit] keys give beyond the FitSpec (e.g. cruse1980's starting
// positions and period-bound targets): the config layer's parser for that kind fills a type
// derived from this one, and the kind's make_fit takes it back.
struct KindFitSpec {
  virtual ~KindFitSpec() = default;
};

struct FitSpec {
  std::vector<FitParameter> parameters;
  Targets targets;
  std::vector<Condition> conditions;  // [fit.conditions]: trials with parameters of their own
  ProblemSettings problem;
  OptimizerOptions optimizer;
  MultistartOptions multistart;
  bool absolute_sigma = false;
  std::vector<std::string> profile;  // parameter ids to profile
  size_t profile_points = 11;
  double profile_span = 3.0;         // +- standard errors
  double output_dt_ms = 1.0;         // best-fit trajectory
  std::string target_set = "default";
  std::vector<std::string> inputs;   // data and parameter files read
  std::shared_ptr<const KindFitSpec> kind;  // the kind's own settings, if it has any
};

// Unset (nullopt / empty) means the [fit] section's value; a given value is checked by
// fit::check_overrides (config/fit_section.hpp), which the CLI and the Python module both reach.
struct FitOverrides {
  std::string data;                         // --data
  std::string data_format;                  // --data-format csv|anipose
  std::string parameters;                   // --parameters
  std::string optimizer;                    // --optimizer
  std::optional<long> multistart;           // --multistart
  std::optional<long> seed;                 // --seed
  std::string target_set;                   // --target-set
  std::optional<long> max_iterations;       // --max-iterations
  int threads = 0;                          // -j (0: [fit] threads, else OpenMP's default)
};

}  // namespace phasmid::fit
