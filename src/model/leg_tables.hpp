#pragma once
// Knops (2013) Appendix A.2, Tables A.10-A.23, as data: geometry, masses and the phase-wise
// spring constants and viscosities of every joint of the front, middle and hind leg.
#include <string>

#include "model/mechanics.hpp"  // JointType

namespace phasmid::model {

const char* joint_name(JointType j);        // "thc", "ctr", "fti"
JointType parse_joint(const std::string& s);  // throws Error

// Per joint: the muscle that increases the angle ("inc": retractor, levator, flexor) and the
// one that decreases it ("dec": protractor, depressor, extensor), and the phase names.
struct JointNaming {
  const char* k_inc;    // "k_R", "k_L", "k_F"
  const char* k_dec;    // "k_P", "k_D", "k_E"
  const char* phase_inc;  // phase in which the angle increases: retraction, levation, flexion
  const char* phase_dec;  // protraction, depression, extension
  const char* muscle_inc; // "ret", "lev", "flx"
  const char* muscle_dec; // "pro", "dep", "ext"
  const char* angle;      // "alpha", "beta", "gamma"
};
JointNaming joint_naming(JointType j);

struct JointTable {
  double angle_min_deg, angle_max_deg;
  double inertia_gmm2;  // tibia inertia (FTi) or effective femur inertia (CTr, ThC)
  // Spring constants (mN/mm^2) of the inc/dec muscles during the inc and dec phases.
  double k_inc_in_inc, k_dec_in_inc, k_inc_in_dec, k_dec_in_dec;
  double b_v_gs;        // viscosity (g/s)
  const char* source;   // table reference
};

// leg: "front", "middle", "hind"; thc_set: "A.16" (default) or "A.17" for the middle leg.
JointTable joint_table(const std::string& leg, JointType j, const std::string& thc_set = "");

struct SegmentTable { double femur_mass_g, femur_length_mm, tibia_mass_g, tibia_length_mm; };
SegmentTable segment_table(const std::string& leg);  // Table A.13

}  // namespace phasmid::model
