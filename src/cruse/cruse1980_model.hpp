#pragma once
// The six coupled relaxation oscillators OL1..OR3 of Cruse (1980), Sect. 2.
// Retraction: output rises at the retraction rate (walking speed) until it reaches the
// oscillator's current threshold (PEP); protraction: output returns to zero (AEP).
// Coupling lowers thresholds: to T1 once a retracting controlling oscillator passes its switch
// position (OL1->OL2->OL3, OL1->OR1->OR2->OR3; released when either oscillator protracts,
// see docs/cruse1980.md), to T2 while OL1 (for OR2) or OL2 (for OR3) protracts.
#include <array>
#include <vector>

#include "cruse/cruse1980_parameters.hpp"

namespace phasmid::cruse {

struct Trajectory {
  std::vector<double> time_ms;
  std::array<std::vector<double>, kLegCount> position;    // oscillator output, position units
  std::array<std::vector<double>, kLegCount> protraction; // 1 while protracting, else 0
  std::array<std::vector<double>, kLegCount> onsets_ms;   // protraction onset times
};

Trajectory simulate(const Parameters& p);

}  // namespace phasmid::cruse
