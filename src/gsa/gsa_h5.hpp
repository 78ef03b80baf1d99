#pragma once
// HDF5 layout of a global sensitivity analysis (docs/gsa.md, docs/hdf5.md), written through
// io::H5Writer and read back for the report:
//   /gsa                      attributes: method ("sobol" | "morris"), the estimator names,
//                             N (base size) or r (trajectories), D, the sampling and bootstrap
//                             settings, the policy for non-finite outputs
//   /gsa/design/              parameter_names, parameter_units, lower, upper, scale,
//                             unit (rows x D design in the unit cube), values (rows x D, in
//                             parameter units)
//   /gsa/<feature>/Y          the feature at every design row (NaN where undefined or failed)
//   /gsa/<feature>/S1, S1_conf, ST, ST_conf [, S2, S2_conf (D x D, upper triangle)]   Sobol'
//   /gsa/<feature>/mu, mu_star, mu_star_conf, sigma                                   Morris
//   /gsa/<feature>/convergence/n and, per n (rows), S1, S1_conf, ST, ST_conf (Sobol') or
//                             mu_star, mu_star_conf, sigma (Morris): indices of nested subsets
// Each feature group carries `units` (the feature's), n_nonfinite, n_dropped, n_used (and
// `variance` for Sobol'). Every dataset has a `units` attribute. "design" is not a feature name.
#include <string>
#include <vector>

#include "gsa/analysis.hpp"
#include "gsa/sampling.hpp"
#include "io/h5_file.hpp"

namespace phasmid::gsa {

struct FeatureResult {
  std::string name, unit;
  std::vector<double> y;  // one output per design row, in row order
  SobolIndices sobol;     // method "sobol"
  MorrisIndices morris;   // method "morris"
  // Indices of nested subsets, the first convergence_n[k] base rows (Sobol') or trajectories
  // (Morris), with their intervals: /gsa/<feature>/convergence (empty: not computed).
  std::vector<std::size_t> convergence_n;
  std::vector<SobolIndices> sobol_convergence;
  std::vector<MorrisIndices> morris_convergence;
};

struct GsaResult {
  std::string method;                 // "sobol" | "morris"
  std::vector<Parameter> parameters;  // name, unit, lower, upper, log_scale
  SaltelliOptions saltelli_options;   // sobol
  SaltelliDesign saltelli;
  MorrisOptions morris_options;       // morris
  MorrisDesign morris;
  BootstrapOptions bootstrap;
  double resolution = 0.1;  // [gsa] resolution: the largest half-width of a resolved index (gsa/resolution.hpp)
  std::vector<FeatureResult> features;

  const std::vector<double>& unit_design() const { return method == "sobol" ? saltelli.unit : morris.unit; }
};

void write_gsa_h5(io::H5Writer& w, const GsaResult& result);
GsaResult read_gsa_h5(const io::H5Reader& r);  // errors name the file and the missing object

}  // namespace phasmid::gsa
