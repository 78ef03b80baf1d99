#pragma once
// Sampling designs of the unit cube for parameter sweeps (docs/sweep.md). All of them are
// deterministic functions of their arguments (own integer arithmetic, no std::*_distribution,
// whose output is implementation-defined), so a sweep's points are the same on every platform.
#include <cstdint>
#include <vector>

namespace phasmid::sweep {

// Unscrambled Sobol' sequence (Joe & Kuo 2008 direction numbers, Gray-code order), points
// 0..n-1 in [0,1)^dim as n x dim row-major; the first point is the origin, as in SciPy's
// `qmc.Sobol(scramble=False)`. dim <= kSobolMaxDim.
constexpr std::size_t kSobolMaxDim = 32;
std::vector<double> sobol_points(std::size_t n, std::size_t dim);

// Latin hypercube: each of the n strata of every dimension holds exactly one point, placed
// uniformly within it; strata are permuted independently per dimension. n x dim row-major.
std::vector<double> lhs_points(std::size_t n, std::size_t dim, std::uint64_t seed);

// splitmix64: small, well-mixed, fully specified generator used by lhs_points.
struct SplitMix64 {
  std::uint64_t state;
  std::uint64_t next();
  double uniform();                        // [0, 1) with 53 random bits
  std::uint64_t below(std::uint64_t n);    // uniform in [0, n), rejection sampling
};

}  // namespace phasmid::sweep
