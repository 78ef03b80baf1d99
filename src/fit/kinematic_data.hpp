#pragma once
// Kinematic recordings as fit targets (docs/fit.md "Data files"): joint angles in degrees over time.
//  - phasmid CSV: a `time_ms` column and one column per angle named `<leg>.<joint>`;
//    Optional `contact.<leg>` columns (0/1, 1 = ground contact) give the leg's stances; a
//    `frame` column with a frame rate may stand in for `time_ms`;
//  - a Stick Insect Locomotion database trial (fit/locomotion_mat.hpp);
//  - Anipose angle CSV: angle columns plus `fnum` (frame number); the frame rate and a
//    column -> `<leg>.<joint>` mapping come from the config.
// Empty cells / NaN mark missing samples and are skipped by the fit.
#include <map>
#include <string>
#include <vector>

#include "features/step_cycles.hpp"

namespace phasmid::fit {

struct KinematicData {
  std::string source;                 // file name, for messages and HDF5 attributes
  std::vector<double> time_ms;        // strictly increasing
  std::vector<std::string> channels;  // "<leg>.<joint>"
  std::vector<std::vector<double>> angles_deg;  // per channel, per sample (NaN: missing)
  std::map<std::string, std::vector<features::Stance>> stances;  // per leg, from contact data
};

// `frame_rate_hz` > 0 lets a `frame` column (frame numbers, time 0 at frame 0) replace time_ms.
KinematicData read_kinematic_csv(const std::string& path, double frame_rate_hz = 0);
KinematicData parse_kinematic_csv(const std::string& text, const std::string& origin, double frame_rate_hz = 0);

// The angles and stances of a phasmid run file (`simulate`, `fit`): /trajectory/angles/<leg>/<joint>
// as `<leg>.<joint>`, stances from /trajectory/footfall/<leg> (1 swing, 0 stance), so that the
// model is summarised as a recording is.
KinematicData read_run_angles(const std::string& path);

// A recording by its extension: `.mat`, a database trial (read_locomotion_mat, with `legs`);
// `.h5`, a phasmid run (read_run_angles); anything else, the phasmid CSV (`legs` unused).
KinematicData read_recording(const std::string& path, double frame_rate_hz = 0, const std::vector<std::string>& legs = {});

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
