#include "model/leg_tables.hpp"

#include "common/error.hpp"

namespace phasmid::model {

const char* joint_name(JointType j) {
  switch (j) {
    case JointType::Thc: return "thc";
    case JointType::Ctr: return "ctr";
    case JointType::Fti: return "fti";
  }
  return "?";
}

JointType parse_joint(const std::string& s) {
  if (s == "thc") return JointType::Thc;
  if (s == "ctr") return JointType::Ctr;
  if (s == "fti") return JointType::Fti;
  throw Error("unknown joint '" + s + "' (expected thc, ctr or fti)");
}

JointNaming joint_naming(JointType j) {
  switch (j) {
    case JointType::Thc: return {"k_R", "k_P", "retraction", "protraction", "ret", "pro", "alpha"};
    case JointType::Ctr: return {"k_L", "k_D", "levation", "depression", "lev", "dep", "beta"};
    case JointType::Fti: return {"k_F", "k_E", "flexion", "extension", "flx", "ext", "gamma"};
  }
  throw Error("bad joint");
}

// Six-leg names (L1..R3, docs/walking_model.md "Six legs") use the tables of their segment.
static std::string segment_of(const std::string& leg) {
  if (leg.size() == 2 && (leg[0] == 'L' || leg[0] == 'R')) {
    if (leg[1] == '1') return "front";
    if (leg[1] == '2') return "middle";
    if (leg[1] == '3') return "hind";
  }
  return leg;
}

JointTable joint_table(const std::string& leg_name, JointType j, const std::string& thc_set) {
  const std::string leg = segment_of(leg_name);
  // {min, max, inertia, k_inc(inc phase), k_dec(inc phase), k_inc(dec phase), k_dec(dec phase), b_v, source}
  if (leg == "middle") {
    switch (j) {
      case JointType::Fti: return {45, 110, 0.1008, 296, 510, 55, 4050, 12.5, "Knops 2013, Table A.14"};
      case JointType::Ctr: return {30, 60, 0.9341, 1868.1, 160.0, 879.21, 800.0, 84.0, "Knops 2013, Table A.15"};
      case JointType::Thc:
        if (thc_set == "A.17") return {28, 128, 0.288, 429, 25, 16, 1000, 25.5, "Knops 2013, Table A.17"};
        return {70, 120, 0.9341, 236.75, 30, 228.42, 300, 25.5, "Knops 2013, Table A.16"};
    }
  } else if (leg == "front") {
    switch (j) {
      case JointType::Fti: return {45, 110, 0.3328, 503.54, 867, 81.39, 5967, 30.6, "Knops 2013, Table A.18"};
      case JointType::Ctr: return {30, 60, 2.38, 2428.5, 208.0, 967.13, 880.0, 134.4, "Knops 2013, Table A.19"};
      case JointType::Thc: return {45, 100, 2.38, 209.39, 82.5, 88.5, 440, 32.5, "Knops 2013, Table A.20"};
    }
  } else if (leg == "hind") {
    switch (j) {
      case JointType::Fti: return {25, 60, 0.255, 197.02, 6300, 53.642, 13000, 19.0, "Knops 2013, Table A.21"};
      case JointType::Ctr: return {30, 60, 1.81, 2428.5, 208.0, 1143.0, 1440.0, 126.0, "Knops 2013, Table A.22"};
      case JointType::Thc: return {90, 145, 2.38, 1108.5, 34.419, 765.39, 698.48, 107.1, "Knops 2013, Table A.23"};
    }
  }
  throw Error("unknown leg '" + leg + "' (expected front, middle, hind or L1..R3)");
}

SegmentTable segment_table(const std::string& leg_name) {
  const std::string leg = segment_of(leg_name);
  if (leg == "front") return {0.0099, 16, 0.0039, 16};
  if (leg == "middle") return {0.0073, 13, 0.0021, 12};
  if (leg == "hind") return {0.0084, 15, 0.0034, 15};
  throw Error("unknown leg '" + leg + "' (expected front, middle or hind)");
}

}  // namespace phasmid::model
