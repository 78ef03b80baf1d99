#pragma once
// Gait features of a Cruse (1980) run, measured on protraction onsets over the last
// `analysis.cycles` periods of OL1 (the leading oscillator).
#include <array>
#include <string>
#include <vector>

#include "cruse/cruse1980_model.hpp"

namespace phasmid::cruse {

struct Features {
  bool locked = false;  // every leg steps once per OL1 period throughout the analysis window
  double period_ms = 0;
  // Graham (1972): time from a hindleg protraction onset to the immediately following
  // protraction onset of the ipsilateral front leg.
  double lag_L3_L1_ms = 0;
  double lag_R3_R1_ms = 0;
  // Onset of each leg after the preceding OL1 onset, as a fraction of the period; onsets up to
  // half the in-phase tolerance before an OL1 onset count as (slightly negative) phase 0.
  std::array<double, kLegCount> phase{};
  std::vector<std::string> in_phase_pairs;  // e.g. "L1-R2": onsets coincide within tolerance
};

Features measure(const Trajectory& run, const Parameters& p);

// True if `pair` (e.g. "L1-R2") is among the run's in-phase pairs.
bool in_phase(const Features& f, const std::string& pair);

// True when two runs show the same coordination pattern: both locked, same period and same
// phases within `tolerance_ms`.
bool same_pattern(const Features& a, const Features& b, double tolerance_ms);

}  // namespace phasmid::cruse
