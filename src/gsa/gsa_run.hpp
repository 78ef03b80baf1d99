#pragma once
// `phasmid gsa` around the sweep engine (docs/gsa.md): the [gsa] section's settings (GsaSpec,
// read by config/gsa_section.hpp), the design they give over the [[sweep.parameter]] ranges
// (whose rows become the points of a sweep, sweep::set_unit_points), and the analysis of the
// finished sweep *file*: the outputs are read from /sweep/features of the HDF5 file, never
// from the sweep's objects, so an analysis can be repeated on any finished sweep of the same
// design. The result is written as /gsa next to /sweep in one file.
//
// Convergence: the design is nested (the first n base rows of a Saltelli design, the first n
// trajectories of a Morris design, are the design of size n), so the indices are also computed
// at n = N, N/2, N/4, ... (down to kMinConvergenceRows) and stored with their intervals; the
// report draws them without recomputing anything.
#include <string>
#include <vector>

#include "gsa/gsa_h5.hpp"
#include "io/h5_file.hpp"

namespace phasmid::gsa {

struct GsaSpec {
  std::string method = "sobol";  // "sobol" | "morris"
  SaltelliOptions saltelli;
  MorrisOptions morris;
  BootstrapOptions bootstrap;
  double resolution = 0.1;  // the largest interval half-width of a resolved index (gsa/resolution.hpp)
  std::vector<std::string> features;  // names of the features to analyse (docs/features.md)
};

// Smallest nested subset of the convergence panel (base rows or trajectories).
constexpr std::size_t kMinConvergenceRows = 8;

// The design of `spec` over `parameters`: method, parameters, options and the design matrix
// filled, no features yet.
GsaResult make_design(const GsaSpec& spec, const std::vector<Parameter>& parameters);

// Reads each feature of spec.features from /sweep/features of a finished sweep file whose
// points are result's design (checked against /sweep/points), and computes its indices and
// convergence. A feature no point produced is analysed as all-NaN (every block dropped).
void analyse_sweep_file(const io::H5Reader& sweep_file, const GsaSpec& spec, GsaResult& result);

// Indices of the first n base rows (Sobol') or trajectories (Morris) of one feature.
void analyse_feature(const GsaResult& design, FeatureResult& f);

// `out` := the /sweep and /parameters groups of `sweep_path` (HDF5 object copies) plus /gsa,
// written atomically (H5Writer); sweep_path may be out itself.
void write_gsa_file(const std::string& sweep_path, const std::string& out, const GsaResult& result,
                    const io::RunInfo& info);

}  // namespace phasmid::gsa
