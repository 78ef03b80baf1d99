#pragma once
// Markov chain Monte Carlo over a LogPosterior (docs/sampling.md). `chains` independent chains
// (split R-hat compares them), each with `temperatures` levels: 1 is adaptive Metropolis alone,
// more is parallel tempering. Each level of a tempered chain samples prior(x) L(x)^beta with
// its own adaptive Metropolis proposal; after every step the chain proposes swaps of the
// states of neighbouring levels (hottest pair first), accepted with probability
// min(1, exp((beta_k - beta_k+1)(log L_k+1 - log L_k))). The ladder starts geometric from
// T = 1 to max_temperature and adapts (Vousden, Farr & Mandel 2016, eq. 13-15): for the
// levels between the coldest and the hottest, log(T_k - T_k-1) moves by
// kappa_t (A_k-1 - A_k) with A the swap acceptances of the step and
// kappa_t = t0 / (nu (t + t0)), which evens out the acceptance of all pairs, during the first
// `ladder_adaptation` share of the steps. Only beta = 1 draws are the posterior's; the others'
// log-likelihoods are kept for thermodynamic integration (sample/evidence.hpp).
//
// Reproducible: every level has its own random stream from (seed, chain, level) and every
// chain one for its swaps, so the draws do not depend on the number of threads evaluating the
// levels of a step in parallel.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sample/adaptive_metropolis.hpp"
#include "sample/log_posterior.hpp"

namespace phasmid::sample {

struct SamplerOptions {
  std::size_t chains = 4;
  std::size_t draws = 2000;        // steps per chain, burn-in included
  std::size_t temperatures = 1;    // levels per chain; > 1: parallel tempering
  double max_temperature = 50.0;   // the hottest level's T = 1/beta (fixed)
  // The hottest level samples the prior (beta = 0; Vousden et al.'s T = infinity) and the
  // others run from T = 1 to max_temperature: what thermodynamic integration needs.
  bool prior_level = false;
  double ladder_t0 = 1000.0;       // Vousden et al.'s t0 and nu
  double ladder_nu = 100.0;
  // The ladder adapts over this share of the draws and then stays fixed, so that the draws
  // after it sample fixed tempered posteriors (thermodynamic integration averages them).
  double ladder_adaptation = 0.5;
  std::uint64_t seed = 1;
  int threads = 0;                 // 0: OpenMP's default
  AdaptiveMetropolisOptions proposal;
  bool IsValid(std::string* why) const;
};

struct SamplerResult {
  std::size_t chains = 0, draws = 0, dim = 0, temperatures = 1;
  bool prior_level = false;            // every chain's hottest level stayed at beta = 0
  std::vector<double> x;               // chains x draws x dim, scaled, beta = 1
  std::vector<double> log_prior;       // chains x draws
  std::vector<double> log_likelihood;  // chains x draws
  std::vector<double> acceptance;      // chains: acceptance rate of the beta = 1 level
  std::vector<double> betas;           // chains x temperatures, the final ladder
  std::vector<double> swap_acceptance; // chains x (temperatures - 1), over the whole run
  std::vector<double> level_log_likelihood;  // chains x temperatures x draws (temperatures > 1)
  std::size_t ladder_fixed_from = 0;   // the first step after the ladder's adaptation
  std::size_t failed_evaluations = 0;  // model runs that failed (rejected proposals)
  double at(std::size_t c, std::size_t i, std::size_t j) const { return x[(c * draws + i) * dim + j]; }
};

// Called after each step with the number of steps done (serially; for a progress line).
using SamplerProgress = std::function<void(std::size_t done)>;

// starts: one point per chain, each of finite posterior; cov0: the initial proposal
// covariance (dim x dim). Throws Error for invalid options or a start outside the support.
SamplerResult run_sampler(const LogPosterior& target, const SamplerOptions& options,
                          const std::vector<std::vector<double>>& starts, const Eigen::MatrixXd& cov0,
                          const SamplerProgress& progress = {});

}  // namespace phasmid::sample
