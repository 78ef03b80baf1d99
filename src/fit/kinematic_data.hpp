#pragma once
// Kinematic recordings as fit targets (docs/fit.md "Data files"): joint angles in degrees over time.
//  - phasmid CSV: a `time_ms` column and one column per angle named `<leg>.<joint>`;
//  - Anipose angle CSV: angle columns plus `fnum` (frame number); the frame rate and a
//    column -> `<leg>.<joint>` mapping come from the config.
// Empty cells / NaN mark missing samples and are skipped by the fit.
#include <map>
#include <string>
#include <vector>

namespace phasmid::fit {

struct KinematicData {
  std::string source;                 // file name, for messages and HDF5 attributes
  std::vector<double> time_ms;        // strictly increasing
  std::vector<std::string> channels;  // "<leg>.<joint>"
  std::vector<std::vector<double>> angles_deg;  // per channel, per sample (NaN: missing)
};

KinematicData read_kinematic_csv(const std::string& path);
KinematicData parse_kinematic_csv(const std::string& text, const std::string& origin);

struct AniposeOptions {
  double frame_rate_hz = 0;                   // required (> 0)
  std::map<std::string, std::string> columns;  // Anipose column -> "<leg>.<joint>"
  double fnum_offset = 0;                     // frame number at t = 0 ms
};
KinematicData read_anipose_csv(const std::string& path, const AniposeOptions& options);
KinematicData parse_anipose_csv(const std::string& text, const std::string& origin, const AniposeOptions& options);

// Writes the phasmid CSV format (used for synthetic recordings).
std::string format_kinematic_csv(const KinematicData& d, const std::string& comment = "");

// "<leg>.<joint>" with leg in front/middle/hind/L1..R3 and joint thc/ctr/fti.
bool is_channel_name(const std::string& s);

}  // namespace phasmid::fit
