#pragma once
// Start points for multistart fits, in the unit cube [0,1)^d (scaled to the bounds by the
// caller): Latin hypercube (stratified, randomly paired) or Sobol (Joe-Kuo direction
// numbers, with a random digital shift). Deterministic for a given seed.
#include <cstdint>
#include <string>
#include <vector>

namespace phasmid::fit {

enum class Sampling { LatinHypercube, Sobol };
Sampling parse_sampling(const std::string& s);  // "lhs" | "sobol"

std::vector<std::vector<double>> latin_hypercube(size_t n, size_t dim, std::uint64_t seed);
// Points 1..n of the Sobol sequence (point 0, the origin, is skipped); seed 0: no shift.
std::vector<std::vector<double>> sobol(size_t n, size_t dim, std::uint64_t seed);
constexpr size_t kSobolMaxDim = 21;

// n points in the box [lo, hi] (scaled parameters).
std::vector<std::vector<double>> start_points(Sampling s, size_t n, const std::vector<double>& lo,
                                              const std::vector<double>& hi, std::uint64_t seed);

}  // namespace phasmid::fit
