#pragma once
// Sampling half of global sensitivity analysis (docs/gsa.md), split from the analysis as in
// SALib: these functions only build designs of the unit cube; the caller evaluates the model
// at every row (after scale_to_parameters) and hands the outputs, row for row, to
// gsa/analysis.hpp. Everything is a deterministic function of the arguments (the project's
// SplitMix64, no std::*_distribution), so a design is the same on every platform.
//
// Saltelli design (Saltelli 2002, 2010): a Sobol' sequence of dimension 2D gives the base
// matrices A (first D columns) and B (last D). Rows are grouped in blocks, one per base row i,
// in SALib's order:
//     A_i, AB^(1)_i, ..., AB^(D)_i, [BA^(1)_i, ..., BA^(D)_i,] B_i
// where AB^(j) is A with column j taken from B and BA^(j) is B with column j taken from A.
// A block has D+2 rows (first and total order) or 2D+2 (with second order). Because the design
// is block-major, the first n blocks are the design of base size n (nested subsets).
//
// Morris design (Morris 1991): r trajectories of D+1 points on the grid {0, 1/(p-1), ..., 1}
// with p levels (p even), step Delta = p / (2(p-1)); consecutive points differ in exactly one
// coordinate, by +-Delta, every coordinate once per trajectory. Optionally r trajectories are
// selected from a larger pool by maximal spread (Campolongo et al. 2007), greedily.
#include <cstdint>
#include <vector>

#include "sweep/sweep_spec.hpp"

namespace phasmid::gsa {

// A varied parameter: name, unit, lower/upper and linear or log scale, exactly as
// [[sweep.parameter]] gives them (only those fields are used).
using Parameter = sweep::SweptParameter;

struct SaltelliOptions {
  std::size_t n_base = 1024;  // N: rows of A and B (a power of two keeps the Sobol' net balanced)
  bool second_order = true;   // add the BA^(j) rows: N(2D+2) instead of N(D+2) rows
  // Randomise the Sobol' sequence: a random linear matrix scramble followed by a random
  // digital shift (Matousek 1998; SciPy's Sobol(scramble=True) does the same), drawn from
  // `seed`. Each point is then uniform on the cube and the net structure is kept; different
  // seeds give independent replicates of the design. Without it the sequence starts at the
  // origin, which `skip` can drop.
  bool scramble = true;
  std::size_t skip = 0;  // leading points of the sequence not used (after scrambling)
  std::uint64_t seed = 0;
};

struct SaltelliDesign {
  std::size_t n_base = 0, dim = 0;
  bool second_order = false;
  std::vector<double> unit;  // rows() x dim, row-major, in [0,1)
  std::size_t block() const { return second_order ? 2 * dim + 2 : dim + 2; }
  std::size_t rows() const { return n_base * block(); }
};

// Sobol' points 0..n-1 in [0,1)^dim (n x dim) after dropping `skip`, linearly scrambled and
// digitally shifted with `seed` when `scramble`.
std::vector<double> scrambled_sobol_points(std::size_t n, std::size_t dim, bool scramble, std::size_t skip,
                                           std::uint64_t seed);

SaltelliDesign saltelli_sample(std::size_t dim, const SaltelliOptions& options);

struct MorrisOptions {
  std::size_t trajectories = 10;  // r
  int levels = 4;                 // p, even and >= 2
  std::size_t pool = 0;           // > r: choose r of this many trajectories by spread; 0: no selection
  std::uint64_t seed = 0;
};

struct MorrisDesign {
  std::size_t dim = 0, trajectories = 0;
  int levels = 0;
  double delta = 0;          // p / (2(p-1))
  std::vector<double> unit;  // trajectories*(dim+1) x dim, row-major, on the p-level grid
  std::size_t rows() const { return trajectories * (dim + 1); }
};

MorrisDesign morris_sample(std::size_t dim, const MorrisOptions& options);

// Unit-cube design (rows x parameters.size()) -> parameter values, the sweep's mapping
// (sweep::map_unit: linear, or log-uniform for scale = "log").
std::vector<double> scale_to_parameters(const std::vector<double>& unit, const std::vector<Parameter>& parameters);

}  // namespace phasmid::gsa
