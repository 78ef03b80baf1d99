#pragma once
// [sample] of `phasmid sample` (docs/sampling.md): the sampler's settings. The problem it
// samples is the one [fit] builds (config/fit_section.hpp).
#include <cstdint>
#include <optional>

#include "config/toml_util.hpp"
#include "sample/sample_run.hpp"

namespace phasmid::config {

// Unset means the [sample] section's value (command-line options of `phasmid sample`).
struct SampleOverrides {
  std::optional<long> chains, draws, seed;
  std::string start;
  int threads = 0;
};

// Limits that keep a run's memory finite (chains x draws x parameters doubles are kept).
inline constexpr std::int64_t kMaxSampleChains = 256;
inline constexpr std::int64_t kMaxSampleTemperatures = 64;
inline constexpr std::int64_t kMaxSampleDraws = 100'000'000;  // chains x draws

// Defaults without a [sample] section; every error names file:line and the key.
sample::SampleSpec sample_spec(const Config& cfg, const SampleOverrides& ov = {});

}  // namespace phasmid::config
