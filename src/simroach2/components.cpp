#include "simroach2/components.hpp"

#include <fmt/format.h>

#include "common/error.hpp"
#include "simroach2/tables.hpp"

namespace phasmid::simroach2 {
namespace {

std::size_t find_row(const Table& t, const std::string& leg_joint) {
  for (std::size_t r = 0; r < t.rows.size(); ++r)
    if (t.text(r, "leg") + " " + t.text(r, "joint") == leg_joint) return r;
  throw Error(fmt::format("{}: no joint '{}' (expected e.g. \"LF ThC2\")", t.origin, leg_joint));
}

void check_muscle_name(const std::string& muscle) {
  if (muscle != "flexor" && muscle != "extensor")
    throw Error(fmt::format("simroach2 muscle must be \"flexor\" or \"extensor\", got \"{}\"", muscle));
}

}  // namespace

MuscleParameters muscle_from_tables(const std::string& leg_joint, const std::string& muscle) {
  check_muscle_name(muscle);
  const auto t3 = load_table("table3_muscle_activation.csv");
  const auto t1 = load_table("table1_rest_lengths.csv");
  MuscleParameters m;  // k_se, k_pe, b, x-offset, steepness: Sect. 2.3 defaults
  const auto r3 = find_row(t3, leg_joint);
  m.activation.amplitude_N = t3.number(r3, muscle + "_amplitude_N");
  m.activation.y_offset_mN = t3.number(r3, muscle + "_y_offset_mN");
  const auto r1 = find_row(t1, leg_joint);
  m.rest_length_m =
      1e-3 * t1.number(r1, muscle == "flexor" ? "spring_flexor_rest_length_mm" : "extensor_rest_length_mm");
  return m;
}

PassiveSpringDamper spring_from_tables(const std::string& leg_joint) {
  const auto t2 = load_table("table2_spring_stiffness_damping.csv");
  const auto t1 = load_table("table1_rest_lengths.csv");
  PassiveSpringDamper s;
  const auto r2 = find_row(t2, leg_joint);
  s.stiffness_N_per_m = t2.number(r2, "stiffness_N_per_m");
  s.damping_Ns_per_m = t2.number(r2, "damping_mg_per_s") * kNsPerM_per_mgPerS;
  s.rest_length_m = 1e-3 * t1.number(find_row(t1, leg_joint), "spring_flexor_rest_length_mm");
  return s;
}

}  // namespace phasmid::simroach2
