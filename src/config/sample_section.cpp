#include "config/sample_section.hpp"

#include "common/error.hpp"

namespace phasmid::config {

namespace {
std::int64_t integer(const Config& cfg, const toml::node& n, const std::string& key, std::int64_t lo, std::int64_t hi) {
  auto v = n.value_exact<std::int64_t>();
  if (!v || *v < lo || *v > hi)
    throw Error(where(cfg, n) + ": [sample] " + key + " must be an integer in [" + std::to_string(lo) + ", " +
                std::to_string(hi) + "]");
  return *v;
}

std::int64_t checked(std::optional<long> v, const char* option, std::int64_t lo, std::int64_t hi) {
  if (*v < lo || *v > hi)
    throw Error(std::string("--") + option + " must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return *v;
}

void read_key(const Config& cfg, const std::string& key, const toml::node& n, sample::SampleSpec& s, bool& tempering) {
  sample::SamplerOptions& o = s.sampler;
  if (key == "chains") o.chains = static_cast<std::size_t>(integer(cfg, n, key, 1, kMaxSampleChains));
  else if (key == "draws") o.draws = static_cast<std::size_t>(integer(cfg, n, key, 20, kMaxSampleDraws));
  else if (key == "temperatures") o.temperatures = static_cast<std::size_t>(integer(cfg, n, key, 1, kMaxSampleTemperatures));
  else if (key == "max_temperature") o.max_temperature = number_in(cfg, n, key, 1.0 + 1e-9, 1e12);
  else if (key == "seed") o.seed = static_cast<std::uint64_t>(integer(cfg, n, key, 0, INT64_MAX));
  else if (key == "target_acceptance") o.proposal.target_acceptance = number_in(cfg, n, key, 0.01, 0.99);
  else if (key == "threads") o.threads = static_cast<int>(integer(cfg, n, key, 0, 256));
  else if (key == "evidence") o.prior_level = boolean(cfg, n, key);
  else if (key == "start") {
    try {
      s.start = sample::parse_start(text(cfg, n, key));
    } catch (const Error& e) {
      throw Error(where(cfg, n) + ": " + e.what());
    }
  } else if (key == "sampler") {
    const std::string v = text(cfg, n, key);
    if (v != "adaptive_metropolis" && v != "parallel_tempering")
      throw Error(where(cfg, n) + ": [sample] sampler must be \"adaptive_metropolis\" or \"parallel_tempering\", got \"" + v + "\"");
    tempering = v == "parallel_tempering";
  }
}
}  // namespace

sample::SampleSpec sample_spec(const Config& cfg, const SampleOverrides& ov) {
  sample::SampleSpec s;
  bool tempering = false;
  const toml::node* sn = cfg.table.get("sample");
  const toml::table* t = sn ? sn->as_table() : nullptr;
  if (sn && !t) throw Error(where(cfg, *sn) + ": 'sample' must be a table ([sample])");
  if (t) {
    check_keys(cfg, *t, "sample", {"sampler", "chains", "draws", "temperatures", "max_temperature", "seed", "start",
                                   "target_acceptance", "threads", "evidence"});
    for (auto&& [k, n] : *t) read_key(cfg, std::string(k.str()), n, s, tempering);
    const toml::node* temps = t->get("temperatures");
    if (tempering && !temps) s.sampler.temperatures = 4;
    if (!tempering && temps && s.sampler.temperatures > 1)
      throw Error(where(cfg, *temps) + ": [sample] temperatures > 1 needs sampler = \"parallel_tempering\"");
    if (s.sampler.prior_level && !tempering)
      throw Error(where(cfg, *t->get("evidence")) + ": [sample] evidence = true needs sampler = \"parallel_tempering\"");
    if (tempering && s.sampler.temperatures < 2)
      throw Error(where(cfg, *temps) + ": [sample] sampler = \"parallel_tempering\" needs temperatures >= 2");
  }
  if (ov.chains) s.sampler.chains = static_cast<std::size_t>(checked(ov.chains, "chains", 1, kMaxSampleChains));
  if (ov.draws) s.sampler.draws = static_cast<std::size_t>(checked(ov.draws, "draws", 20, kMaxSampleDraws));
  if (ov.seed) s.sampler.seed = static_cast<std::uint64_t>(checked(ov.seed, "seed", 0, INT64_MAX));
  if (!ov.start.empty()) s.start = sample::parse_start(ov.start);
  if (ov.threads) s.sampler.threads = ov.threads;
  if (s.sampler.chains * s.sampler.draws > static_cast<std::size_t>(kMaxSampleDraws))
    throw Error(cfg.path + ": [sample] chains x draws = " + std::to_string(s.sampler.chains * s.sampler.draws) +
                " exceeds " + std::to_string(kMaxSampleDraws) + " kept draws");
  return s;
}

}  // namespace phasmid::config
