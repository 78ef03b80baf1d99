#pragma once
// Analysis half of global sensitivity analysis (docs/gsa.md): indices from the outputs of a
// design built by gsa/sampling.hpp, one output per design row, in the design's row order.
//
// Sobol' indices, with V the variance of the outputs of A and B together (divisor 2n):
//   first order  S1_j  = mean(f(B) (f(AB^(j)) - f(A))) / V                (Saltelli et al. 2010)
//   total order  ST_j  = mean((f(A) - f(AB^(j)))^2) / (2 V)               (Jansen 1999)
//   second order S2_jk = mean(f(BA^(j)) f(AB^(k)) - f(A) f(B)) / V - S1_j - S1_k   (Saltelli 2002)
// These are SALib's estimators, so results can be compared with it.
//
// Failed or undefined outputs (NaN or infinite, e.g. a feature of a point that does not
// oscillate): a base row's whole block (A_i, B_i and its AB/BA rows) is dropped when any of its
// outputs is not finite, so that every estimator sees the same matched rows; the counts are
// returned. The indices then describe the feature where it is defined, which is only the
// unconditional answer if failures do not depend on the parameters (docs/gsa.md).
//
// Confidence intervals: the base rows (blocks, for Morris trajectories) that were used are
// resampled with replacement `resamples` times and every index is recomputed; the interval is
// index +- z * (standard deviation of the bootstrap replicates, divisor B-1), z the standard
// normal quantile at (1 + confidence)/2 (normal approximation, as SALib). *_conf holds the
// half-width z * sd. A replicate whose resampled outputs are all equal (no variance; possible
// for rare 0/1 outputs) has no indices and is left out of the standard deviation.
#include <cstdint>
#include <vector>

#include "gsa/sampling.hpp"

namespace phasmid::gsa {

struct BootstrapOptions {
  std::size_t resamples = 1000;  // B; 0 leaves the *_conf values NaN
  double confidence = 0.95;      // in (0, 1)
  std::uint64_t seed = 0;
};

// Failed-output bookkeeping of one feature.
struct OutputCounts {
  std::size_t n_nonfinite = 0;  // outputs that are NaN or infinite
  std::size_t n_dropped = 0;    // blocks (Sobol': base rows; Morris: trajectories) dropped for them
  std::size_t n_used = 0;       // blocks the indices are computed from
};

struct SobolIndices {
  std::vector<double> S1, S1_conf, ST, ST_conf;  // per parameter
  std::vector<double> S2, S2_conf;  // D x D row-major, (j, k) for j < k, NaN elsewhere; empty without second order
  double variance = 0;              // V, in the feature's unit squared
  OutputCounts counts;
};

struct MorrisIndices {
  std::vector<double> mu, mu_star, mu_star_conf, sigma;  // per parameter, in the feature's unit
  OutputCounts counts;
};

// Standard normal quantile (inverse CDF) for p in (0, 1).
double normal_quantile(double p);

// `y` has dim(second_order ? 2D+2 : D+2) values per base row; the first n blocks of a design's
// outputs are the outputs of the base-size-n design (convergence with nested subsets).
SobolIndices sobol_analyze(std::size_t dim, bool second_order, const std::vector<double>& y,
                           const BootstrapOptions& bootstrap);

// Elementary effects EE = (f(x + e_j dDelta) - f(x)) / (d Delta), d = +-1, in unit-cube
// coordinates (SALib's convention): mu = mean EE, mu_star = mean |EE| (Campolongo 2007),
// sigma = standard deviation (divisor r-1). The changed coordinate and its direction are read
// from the design. A trajectory with any non-finite output is dropped whole.
MorrisIndices morris_analyze(const MorrisDesign& design, const std::vector<double>& y,
                             const BootstrapOptions& bootstrap);

}  // namespace phasmid::gsa
