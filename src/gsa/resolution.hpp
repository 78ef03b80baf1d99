#pragma once
// Whether an index is resolved at the design's size (docs/gsa.md, "Resolved indices"), and the
// size that would resolve the ones that are not.
//
// A Sobol' index (S1, ST, S2) is resolved when its interval half-width is at most `threshold`
// and the estimate lies within [-threshold/2, 1 + threshold/2]: indices are fractions of a
// variance, so an estimate outside [0, 1] by more than that is sampling error, whatever its
// interval says. A Morris mu* is resolved when its half-width is at most threshold times the
// largest mu* of the feature (mu* has the feature's unit; what matters is the ranking). An
// index whose interval is undefined (NaN: too few usable rows, no variance) is not resolved.
//
// The size that would resolve an index comes from the nested subsets (gsa_run.hpp): the
// half-widths at n = N/2^k are fitted by c / sqrt(n) (the rate of a bootstrap of means; c from
// the mean of log(half-width) + log(n)/2 over the subsets, so one noisy subset does not set
// it) and solved for 0.8 times the target half-width (threshold, or threshold/2 for an
// estimate out of range; 2N for an estimate out of range whose interval is already narrow):
// intervals from few rows are noisy themselves, and the margin keeps the named size enough. The feature's
// estimate is the largest over its unresolved indices, rounded up to a power of two (a
// balanced Sobol' net), or NaN when no unresolved index has a finite interval.
#include <cstddef>
#include <string>
#include <vector>

#include "gsa/gsa_h5.hpp"

namespace phasmid::gsa {

struct FeatureResolution {
  std::vector<char> S1, ST, S2;  // Sobol': 1 resolved, 0 not; S2 D x D (upper triangle; 1 elsewhere)
  std::vector<char> mu_star;     // Morris
  std::size_t n_unresolved = 0;     // all indices, S2 included
  std::size_t n_unresolved_s2 = 0;  // of which second-order
  double n_to_resolve = 0;  // base rows (Sobol') or trajectories (Morris); 0: all resolved; NaN: unknown
  bool all_resolved() const { return n_unresolved == 0; }
};

// "must be in (0, 1]" style message naming `threshold` when it is not a usable threshold; empty when valid.
std::string resolution_error(double threshold);

// At result.resolution, from the feature's indices and their nested subsets.
FeatureResolution resolve(const GsaResult& result, const FeatureResult& feature);

}  // namespace phasmid::gsa
