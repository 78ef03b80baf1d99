#pragma once
// `phasmid report`: any phasmid HDF5 file -> one self-contained HTML page.
//
// extract() walks the file generically (docs/hdf5.md layout): which groups exist decides what
// goes into the JSON, and so which figures the page draws. Long time series are reduced to at
// most `max_points` samples with min/max decimation (spikes survive). render_html() inlines
// that JSON, the embedded template reports/report.{html,css,js} and the vendored chart library
// (reports/vendor/) into one page that needs no network access to view.
#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace phasmid::report {

constexpr std::size_t kDefaultMaxPoints = 5000;

nlohmann::json extract(const std::string& h5_path, std::size_t max_points = kDefaultMaxPoints);
std::string render_html(const nlohmann::json& data);

// RUN.h5 -> RUN.html next to it.
std::string default_output_path(const std::string& h5_path);
// extract + render + write atomically (temporary name in the same directory, then rename).
void write_report(const std::string& h5_path, const std::string& html_path);

// --- pieces exposed for tests ---
// Indices to keep so that at most max_points remain: first, last, and per bucket the min and
// the max (in time order). Returns 0..n-1 when n <= max_points.
std::vector<std::size_t> decimate_indices(const std::vector<double>& y, std::size_t max_points);
// Time intervals [t_start, t_end] where flag >= 0.5 (swing / protraction).
std::vector<std::pair<double, double>> intervals_where(const std::vector<double>& t,
                                                       const std::vector<double>& flag);
// JSON text safe to place inside <script type="application/json">: every '<' escaped.
std::string json_for_script(const nlohmann::json& j);

}  // namespace phasmid::report
