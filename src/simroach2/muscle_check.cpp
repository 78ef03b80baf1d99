#include "simroach2/muscle_check.hpp"

#include <cmath>

#include "simroach2/muscle.hpp"

namespace phasmid::simroach2 {

std::vector<MuscleCheckRow> check_muscles(const Table& t) {
  std::vector<MuscleCheckRow> out;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    for (const std::string muscle : {"flexor", "extensor"}) {
      MuscleCheckRow row;
      row.joint = t.text(r, "leg") + " " + t.text(r, "joint");
      row.muscle = muscle;
      const std::string a_col = muscle + "_amplitude_N", y_col = muscle + "_y_offset_mN";
      row.amplitude_N = t.number(r, a_col);
      row.y_offset_mN = t.number(r, y_col);
      ActivationCurve curve;  // x-offset -50 mV, steepness 300 (Sect. 2.3)
      curve.amplitude_N = row.amplitude_N;
      curve.y_offset_mN = row.y_offset_mN;
      row.force_at_rest_mN = 1e3 * curve.force_N(kMotorNeuronRestMV);
      ActivationCurve unit = curve;
      unit.amplitude_N = 1.0;
      unit.y_offset_mN = 0.0;
      const double sigmoid_at_rest = unit.force_N(kMotorNeuronRestMV);
      row.rounding_bound_mN = 1e3 * sigmoid_at_rest * 0.5 * std::pow(10.0, -printed_decimals(t.text(r, a_col))) +
                              0.5 * std::pow(10.0, -printed_decimals(t.text(r, y_col)));
      row.consistent = std::abs(row.force_at_rest_mN) <= row.rounding_bound_mN;
      out.push_back(row);
    }
  }
  return out;
}

}  // namespace phasmid::simroach2
