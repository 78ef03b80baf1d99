#include "sample/sampler.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <random>

#include "common/error.hpp"

namespace phasmid::sample {

bool SamplerOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (chains < 1) return fail("chains must be at least 1");
  if (draws < 20) return fail("draws must be at least 20 (the burn-in rule cuts chains in twentieths)");
  if (temperatures < 1) return fail("temperatures must be at least 1");
  if (temperatures > 1 && !(max_temperature > 1 && std::isfinite(max_temperature)))
    return fail("max_temperature must be a finite number above 1");
  if (!(ladder_t0 > 0) || !(ladder_nu > 0)) return fail("the ladder's t0 and nu must be positive");
  if (!(ladder_adaptation >= 0 && ladder_adaptation <= 1)) return fail("the ladder's adaptation share must lie in [0, 1]");
  if (prior_level && temperatures < 2) return fail("a prior level (evidence) needs temperatures >= 2");
  if (threads < 0) return fail("threads must not be negative");
  return proposal.IsValid(why);
}

namespace {
struct Level {
  Eigen::VectorXd x;
  PosteriorValue v;
  AdaptiveMetropolis am;
  std::mt19937_64 rng;
  double beta = 1.0;
  std::size_t accepted = 0;
};

struct Chain {
  std::vector<Level> levels;  // levels[0]: beta = 1
  std::mt19937_64 swap_rng;
  std::vector<double> swap_accepted;
};

std::mt19937_64 stream(std::uint64_t seed, std::uint64_t chain, std::uint64_t level) {
  std::seed_seq s{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                  static_cast<std::uint32_t>(chain), static_cast<std::uint32_t>(level)};
  return std::mt19937_64(s);
}

std::vector<double> as_std(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

// One Metropolis step of one level; true if the proposal's model run failed.
bool step(const LogPosterior& target, Level& l) {
  const Eigen::VectorXd y = l.am.propose(l.x, l.rng);
  const PosteriorValue vy = target(as_std(y));
  const double log_ratio = vy.tempered(l.beta) - l.v.tempered(l.beta);
  const double alpha = std::isnan(log_ratio) ? 0.0 : std::min(1.0, std::exp(log_ratio));
  // Drawn on every step, so that each stream advances the same way whatever was accepted.
  const double u = std::uniform_real_distribution<double>()(l.rng);
  if (u < alpha) {
    l.x = y;
    l.v = vy;
    ++l.accepted;
  }
  l.am.adapt(l.x, alpha);
  return vy.failed;
}

// Vousden, Farr & Mandel (2016): even out the swap acceptances A (this step's probabilities)
// by moving the levels between the coldest and the hottest; a step that would reorder them is
// skipped.
void adapt_ladder(Chain& c, const std::vector<double>& a, std::size_t t, const SamplerOptions& o) {
  const std::size_t k_levels = c.levels.size();
  if (k_levels < 3) return;
  const double kappa = o.ladder_t0 / (o.ladder_nu * (static_cast<double>(t) + o.ladder_t0));
  std::vector<double> temp(k_levels);
  for (std::size_t k = 0; k < k_levels; ++k) temp[k] = 1.0 / c.levels[k].beta;
  std::vector<double> next = temp;
  for (std::size_t k = 1; k + 1 < k_levels; ++k)
    next[k] = next[k - 1] + std::exp(std::log(temp[k] - temp[k - 1]) + kappa * (a[k - 1] - a[k]));
  if (!(next[k_levels - 2] < next[k_levels - 1])) return;
  for (std::size_t k = 1; k + 1 < k_levels; ++k) c.levels[k].beta = 1.0 / next[k];
}

void propose_swaps(Chain& c, std::size_t t, bool adapt, const SamplerOptions& o) {
  const std::size_t k_levels = c.levels.size();
  if (k_levels < 2) return;
  std::vector<double> a(k_levels - 1, 0.0);
  for (std::size_t k = k_levels - 1; k-- > 0;) {
    Level &cold = c.levels[k], &hot = c.levels[k + 1];
    const double log_ratio = (cold.beta - hot.beta) * (hot.v.log_likelihood - cold.v.log_likelihood);
    a[k] = std::isnan(log_ratio) ? 0.0 : std::min(1.0, std::exp(log_ratio));
    if (std::uniform_real_distribution<double>()(c.swap_rng) < a[k]) {
      std::swap(cold.x, hot.x);
      std::swap(cold.v, hot.v);
      c.swap_accepted[k] += 1;
    }
  }
  if (adapt) adapt_ladder(c, a, t, o);
}

// Geometric from T = 1 to max_temperature over the finite levels; beta = 0 for a prior level.
double initial_beta(const SamplerOptions& o, std::size_t k) {
  const std::size_t finite = o.prior_level ? o.temperatures - 1 : o.temperatures;
  if (k >= finite) return 0.0;
  return finite == 1 ? 1.0 : std::pow(o.max_temperature, -double(k) / double(finite - 1));
}

std::vector<Chain> initial_chains(const LogPosterior& target, const SamplerOptions& o,
                                  const std::vector<std::vector<double>>& starts, const Eigen::MatrixXd& cov0) {
  std::vector<Chain> chains;
  for (std::size_t c = 0; c < o.chains; ++c) {
    const Eigen::VectorXd x0 = Eigen::Map<const Eigen::VectorXd>(starts[c].data(), static_cast<long>(starts[c].size()));
    const PosteriorValue v0 = target(starts[c]);
    if (!std::isfinite(v0.tempered(1.0)))
      throw Error("chain " + std::to_string(c) + ": the start has zero posterior density (" +
                  (v0.failed ? "the model run failed" : "outside the bounds or the prior's support") + ")");
    Chain ch{{}, stream(o.seed, c, o.temperatures), std::vector<double>(o.temperatures - 1, 0.0)};
    for (std::size_t k = 0; k < o.temperatures; ++k)
      ch.levels.push_back(Level{x0, v0, AdaptiveMetropolis(x0, cov0, o.proposal), stream(o.seed, c, k), initial_beta(o, k), 0});
    chains.push_back(std::move(ch));
  }
  return chains;
}

// One step of every level of every chain, in parallel; returns the failed model runs.
std::size_t step_all(const LogPosterior& target, std::vector<Level*>& levels, int threads) {
  std::size_t failed = 0;
  std::exception_ptr error;
  const long n = static_cast<long>(levels.size());
#pragma omp parallel for schedule(dynamic) num_threads(threads) reduction(+ : failed)
  for (long i = 0; i < n; ++i) {
    try {
      failed += step(target, *levels[static_cast<std::size_t>(i)]) ? 1 : 0;
    } catch (...) {
#pragma omp critical(phasmid_sampler_error)
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
  return failed;
}

void record(SamplerResult& r, const std::vector<Chain>& chains, std::size_t i) {
  for (std::size_t c = 0; c < chains.size(); ++c) {
    const Level& l = chains[c].levels[0];
    std::copy(l.x.data(), l.x.data() + l.x.size(), r.x.begin() + static_cast<long>((c * r.draws + i) * r.dim));
    r.log_prior[c * r.draws + i] = l.v.log_prior;
    r.log_likelihood[c * r.draws + i] = l.v.log_likelihood;
    if (r.temperatures > 1)
      for (std::size_t k = 0; k < r.temperatures; ++k)
        r.level_log_likelihood[(c * r.temperatures + k) * r.draws + i] = chains[c].levels[k].v.log_likelihood;
  }
}

void finish(SamplerResult& r, const std::vector<Chain>& chains) {
  for (const Chain& ch : chains) {
    r.acceptance.push_back(double(ch.levels[0].accepted) / double(r.draws));
    for (const Level& l : ch.levels) r.betas.push_back(l.beta);
    for (double s : ch.swap_accepted) r.swap_acceptance.push_back(s / double(r.draws));
  }
}
}  // namespace

SamplerResult run_sampler(const LogPosterior& target, const SamplerOptions& o,
                          const std::vector<std::vector<double>>& starts, const Eigen::MatrixXd& cov0,
                          const SamplerProgress& progress) {
  std::string why;
  if (!o.IsValid(&why)) throw Error("[sample] " + why);
  if (starts.size() != o.chains) throw Error("[sample] " + std::to_string(starts.size()) + " starts for " + std::to_string(o.chains) + " chains");
  std::vector<Chain> chains = initial_chains(target, o, starts, cov0);
  std::vector<Level*> levels;
  for (Chain& c : chains)
    for (Level& l : c.levels) levels.push_back(&l);
  SamplerResult r;
  r.chains = o.chains, r.draws = o.draws, r.dim = target.dim(), r.temperatures = o.temperatures;
  r.prior_level = o.prior_level;
  r.x.assign(r.chains * r.draws * r.dim, 0.0);
  r.log_prior.assign(r.chains * r.draws, 0.0);
  r.log_likelihood.assign(r.chains * r.draws, 0.0);
  if (r.temperatures > 1) r.level_log_likelihood.assign(r.chains * r.temperatures * r.draws, 0.0);
  r.ladder_fixed_from = r.temperatures > 2 ? static_cast<std::size_t>(std::ceil(o.ladder_adaptation * double(o.draws))) : 0;
  const int threads = o.threads > 0 ? o.threads : omp_get_max_threads();
  for (std::size_t i = 0; i < o.draws; ++i) {
    r.failed_evaluations += step_all(target, levels, threads);
    for (Chain& c : chains) propose_swaps(c, i, i < r.ladder_fixed_from, o);
    record(r, chains, i);
    if (progress) progress(i + 1);
  }
  finish(r, chains);
  return r;
}

}  // namespace phasmid::sample
