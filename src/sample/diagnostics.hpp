#pragma once
// Whether to believe a chain (docs/sampling.md, "Diagnostics"). Every function takes the draws
// of one parameter as chains[c][i] (c chains of equal length n >= 4).
//  - effective_sample_size: Stan's multi-chain estimator (Vehtari et al. 2021, eq. 10-11,
//    without the rank normalisation): autocorrelations from the chains' autocovariances and the
//    between-chain variance, summed in pairs with Geyer's (1992) initial monotone sequence.
//  - split_rhat: each chain cut in halves, then Gelman & Rubin's potential scale reduction
//    sqrt(var+ / W) over the 2c half-chains (Gelman et al., BDA3, Section 11.4).
//  - geweke_z: the difference of the means of a chain's first 10 % and last 50 %, in units of
//    its standard error (Geweke 1992), with both parts' variances of the mean from the last
//    half's spectral density at zero (variance x autocorrelation time), which stationarity
//    makes common to both: the first part's own would grow with the very drift under test.
//  - burn_in: the first of the starts n/20, 2n/20, ... from which every chain's and every
//    parameter's Geweke |z| stays below the two-sided 5 % level, Bonferroni-corrected for the
//    number of tests (chains x parameters); n if there is none (pyPESTO's geweke_test rule).
//    The first twentieth always goes: Geweke's test cannot see a transient much shorter than
//    its 10 % window, and a chain started from a draw of the prior has one (a linear-Gaussian
//    posterior's sd came out 3 % wide, 4 Monte Carlo errors, with it kept).
#include <cstddef>
#include <string>
#include <vector>

namespace phasmid::sample {

using Chains = std::vector<std::vector<double>>;

struct Moments {
  double mean = 0, variance = 0;  // variance with n - 1
};
Moments moments(const std::vector<double>& v);  // v.size() >= 2

double effective_sample_size(const Chains& chains);
double split_rhat(const Chains& chains);
double geweke_z(const std::vector<double>& chain);
// draws[p] are the chains of parameter p.
std::size_t burn_in(const std::vector<Chains>& draws);

// The one-line warnings of docs/sampling.md for a parameter: R-hat above 1.01, ESS below 100.
std::vector<std::string> diagnostic_warnings(const std::string& parameter, double ess, double rhat);

// The two-sided normal quantile: |z| exceeded with probability alpha.
double normal_two_sided_quantile(double alpha);

}  // namespace phasmid::sample
