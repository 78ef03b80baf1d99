#pragma once
// What every report panel reads with: shape checks on HDF5 datasets, numbers rounded for the
// page, decimated time series, and the list of groups the page could not draw (out["ignored"]).
// A panel file (trajectory_panels.cpp, fit_panels.cpp, ...) turns one top-level group into JSON
// with these; report.cpp assembles the page.
#include <hdf5.h>

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <vector>

#include "io/h5_file.hpp"

namespace phasmid::report {

// A number for the page: 6 significant digits (plenty for a figure, and the inlined JSON stays
// small); NaN and infinities become null.
nlohmann::json num(double v);
nlohmann::json nums(const std::vector<double>& v);

// The `units` attribute of `path`, "" without one.
std::string units_of(const io::H5Reader& r, const std::string& path);

bool is_dataset(const io::H5Reader& r, const std::string& path);
bool is_string_dataset(const io::H5Reader& r, const std::string& path);
bool is_numeric_dataset(const io::H5Reader& r, const std::string& path);
// Elements of a dataset of dimensions d.
std::size_t n_elements(const std::vector<hsize_t>& d);
// The strings of `path`, none if it is not a string dataset.
std::vector<std::string> strings_or_empty(const io::H5Reader& r, const std::string& path);

// Every dataset below `group`, as paths relative to it ("a/b"), in name order, appended to out.
// Throws Error on a group nested too deep (a cycle) or too many datasets.
void walk(const io::H5Reader& r, const std::string& group, const std::string& prefix,
          std::vector<std::string>& out, int depth = 0);

// A time series for the page: y values, plus its own t when it had to be decimated to max_points.
nlohmann::json series(const std::vector<double>& t, const std::vector<double>& y, std::size_t max_points);

// Lists `path` in out["ignored"] (drawn nowhere on the page).
void note_ignored(nlohmann::json& out, const std::string& path);

// Named per-parameter vectors below `group` (sensitivity/features, sweep/features, ...): every
// numeric dataset of `expected` elements; the others are listed as ignored.
nlohmann::json named_vectors(const io::H5Reader& r, nlohmann::json& out, const std::string& group,
                             std::size_t expected);

}  // namespace phasmid::report
