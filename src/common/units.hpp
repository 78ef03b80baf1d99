#pragma once
// Degree/radian conversion, the one unit boundary inside the code: parameters, targets and
// HDF5 files hold angles in degrees, joint states are in radians (docs/model.md "Units").
//
// Two forms with different rounding: `x * kRadPerDeg` multiplies by the rounded constant
// pi/180, `deg_to_rad(x)` computes (x * pi) / 180; the results can differ in the last bit.
// Each call site keeps its form because switching it changes trajectories, features and fits
// in the last bit (likewise kDegPerRad against rad_to_deg). New code may use either.
#include <cmath>

namespace phasmid::units {

inline constexpr double kRadPerDeg = M_PI / 180.0;
inline constexpr double kDegPerRad = 180.0 / M_PI;

// (x * pi) / 180, rounded after each operation.
constexpr double deg_to_rad(double deg) { return deg * M_PI / 180.0; }
// (x * 180) / pi, rounded after each operation.
constexpr double rad_to_deg(double rad) { return rad * 180.0 / M_PI; }

}  // namespace phasmid::units
