#pragma once
// The report's panels: one function per top-level group of a phasmid file, each in its own
// file (<kind>_panels.cpp), turning the group into the JSON that reports/report.js draws
// (docs/reports.md). Those that take `out` fill out["<group>"] and list what they cannot show
// in out["ignored"]; all throw Error on a group whose datasets are inconsistent, which
// extract() lists as unreadable.
#include <nlohmann/json.hpp>

#include <cstddef>

namespace phasmid::io {
class H5Reader;
}

namespace phasmid::report {

// /trajectory of a `simulate` file (docs/hdf5.md): joint angles and velocities, membrane
// potentials, footfall and protraction intervals, Cruse-model leg positions; every series
// decimated to at most max_points (trajectory_panels.cpp).
void extract_trajectory(const io::H5Reader& r, nlohmann::json& out, std::size_t max_points);

// /parameters and /features of any run file: name, value and units per row (run_panels.cpp).
void extract_parameters(const io::H5Reader& r, nlohmann::json& out);
void extract_features(const io::H5Reader& r, nlohmann::json& out);

// /sensitivity (docs/sensitivity.md): feature gradients, absolute and relative, Floquet
// multipliers and the phase response curve (sensitivity_panels.cpp).
void extract_sensitivity(const io::H5Reader& r, nlohmann::json& out);

// /fit (docs/fit.md): estimates with standard errors, correlation, cost history, multistart
// costs, and the data against the fitted model's kinematics (fit_panels.cpp).
void extract_fit(const io::H5Reader& r, nlohmann::json& out, std::size_t max_points);

// /sweep (docs/sweep.md): points, per-point features, gait class and status, swept [model]
// options, and the range analysis of a one-at-a-time sweep (sweep_panels.cpp).
void extract_sweep(const io::H5Reader& r, nlohmann::json& out);

// /gsa (docs/gsa.md): per feature the indices with their interval half-widths, the
// failed-output counts and the convergence of nested subsets, as the analysis stored them (read
// with gsa::read_gsa_h5; nothing is recomputed). Returns the JSON of out["gsa"] (gsa_panels.cpp).
nlohmann::json extract_gsa(const io::H5Reader& r);

// /continuation of a `continue` file (docs/continuation.md): parameter, period, tracked
// features, stability, multipliers and special points (continuation_panels.cpp).
void extract_continuation(const io::H5Reader& r, nlohmann::json& out);

}  // namespace phasmid::report
