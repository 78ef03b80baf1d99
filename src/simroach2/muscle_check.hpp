#pragma once
// Consistency check of Table 3: the supplement (Sect. 2.3) says each y-offset was constrained
// so that the active force is zero with the motor neuron at -60 mV.
#include <string>
#include <vector>

#include "simroach2/tables.hpp"

namespace phasmid::simroach2 {

struct MuscleCheckRow {
  std::string joint;   // "LF ThC2"
  std::string muscle;  // "flexor" | "extensor"
  double amplitude_N = 0;
  double y_offset_mN = 0;
  double force_at_rest_mN = 0;  // active force at -60 mV from the printed values
  // What printing to the given decimals can explain: half a unit in the last printed digit of
  // the amplitude (times the sigmoid at -60 mV) plus half a unit of the y-offset.
  double rounding_bound_mN = 0;
  bool consistent = false;      // |force_at_rest| <= rounding_bound
};

constexpr double kMotorNeuronRestMV = -60.0;  // Sect. 2.3

std::vector<MuscleCheckRow> check_muscles(const Table& table3);

}  // namespace phasmid::simroach2
