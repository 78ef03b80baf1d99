#pragma once
// Model evidence by thermodynamic integration over the tempered levels (docs/sampling.md,
// "Model evidence"): log Z = integral over beta from 0 to 1 of E_beta[log L], the expectation
// under the tempered posterior prior(x) L(x)^beta (Lartillot & Philippe 2006; Friel & Pettitt
// 2008), by the trapezoid rule with its Euler-Maclaurin correction (the integrand's slope is
// Var_beta[log L], measured at every level; Friel, Hurn & Wyse 2014) over each chain's fixed
// ladder, which must include beta = 0
// (the prior level, [sample] evidence = true), averaged over the chains. Draws are those
// after `from` (the ladder's adaptation and the burn-in). Two errors:
//  - Monte Carlo: each level's mean has variance var/ESS; the trapezoid's weights carry them
//    to log Z (levels and chains taken as independent; the correction's variances' own noise
//    is left out);
//  - discretisation: the difference to the same rule over every other level (from beta = 0,
//    keeping beta = 1), divided by 15: the corrected rule's error falls as h^4, so halving the
//    levels multiplies it by 16 (Richardson), where the integrand is smooth.
// As log L leaves out the Gaussian normalisation of fixed noises, log Z is up to that
// constant: Bayes factors compare configs fitted to the same data with the same fixed noises.
#include <cstddef>
#include <string>
#include <vector>

#include "sample/sampler.hpp"

namespace phasmid::sample {

struct Evidence {
  bool ok = false;
  std::string note;  // why there is no estimate, when !ok
  double log_evidence = 0, mc_error = 0, discretisation_error = 0;
  std::vector<double> betas;                // chain 0's ladder, coldest first
  std::vector<double> mean_log_likelihood;  // per level, mean over chains and kept draws
  double error() const;                     // the two combined in quadrature
};

Evidence thermodynamic_integration(const SamplerResult& r, std::size_t from);

}  // namespace phasmid::sample
