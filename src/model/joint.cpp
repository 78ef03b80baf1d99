#include "model/joint.hpp"

#include <cmath>

#include "common/units.hpp"

namespace phasmid::model {
namespace {
const char* kA10 = "Knops 2013, Table A.10 (Guschlbauer et al. 2007)";
const char* kA11 = "Knops 2013, Table A.11 (Bassler 1983)";
const char* kA12 = "Knops 2013, Table A.12 (Bassler 1983)";

// Smallest admissible viscosity, g/s (docs/model.md "Admissible ranges"): without damping the
// joint equations have no dissipation and the angle swings through every anatomical limit;
// 0.01 g/s is a documented choice, 1250x below the smallest b_v of Tables A.14-A.23 (12.5 g/s).
constexpr double kMinViscosityGs = 0.01;

FtiGeometry<double> fti_geometry() { return {0.28, 1.41, 2.11, 1.05, 1.50, 0.34, 0.42}; }
CtrGeometry<double> ctr_geometry() { return {3.5, 1.0, 1.05, 1.50}; }
ThcGeometry<double> thc_geometry() { return {2.0, 2.5, 1.0, 1.5}; }
}  // namespace

JointMechanics define_joint_mechanics(ParameterSet& ps, const std::string& leg, JointType type,
                                      const std::string& thc_set) {
  JointMechanics j{};
  j.type = type;
  j.prefix = leg + "." + joint_name(type);
  const std::string pre = j.prefix + ".";
  auto add = [&](const std::string& n, double v, const char* unit, const std::string& src, const std::string& desc,
                 double lo = 0.0, double hi = INFINITY) {
    return ps.add({pre + n, v, unit, src, desc, lo, hi});
  };
  for (auto& x : j.geom) x = 0;
  switch (type) {
    case JointType::Fti: {
      auto g = fti_geometry();
      j.geom[0] = add("d", g.d, "mm", kA10, "extensor tendon lever (flexor lever is 2d)", 1e-6);
      j.geom[1] = add("l_E0", g.l_E0, "mm", kA10, "extensor fibre length at gamma = 90 deg", 1e-6);
      j.geom[2] = add("l_F0", g.l_F0, "mm", kA10, "flexor fibre length at gamma = 90 deg", 1e-6);
      j.geom[3] = add("l_E_min", g.l_E_min, "mm", kA10, "unstrained extensor fibre length");
      j.geom[4] = add("l_F_min", g.l_F_min, "mm", kA10, "unstrained flexor fibre length");
      j.geom[5] = add("h_E", g.h_E, "mm", kA10, "extensor tendon-cuticle distance");
      j.geom[6] = add("h_F", g.h_F, "mm", kA10, "flexor tendon-cuticle distance");
      break;
    }
    case JointType::Ctr: {
      auto g = ctr_geometry();
      j.geom[0] = add("d", g.d, "mm", kA11, "distance AB: muscle length at beta = 0", 1e-6);
      j.geom[1] = add("r", g.r, "mm", kA11, "radius of the trochanter lever", 1e-6);
      j.geom[2] = add("l_L_min", g.l_L_min, "mm", kA11, "unstrained levator length");
      j.geom[3] = add("l_D_min", g.l_D_min, "mm", kA11, "unstrained depressor length");
      break;
    }
    case JointType::Thc: {
      auto g = thc_geometry();
      j.geom[0] = add("d", g.d, "mm", kA12, "insertion distance on the coxa/femur", 1e-6);
      j.geom[1] = add("r", g.r, "mm", kA12, "insertion distance on the thorax", 1e-6);
      j.geom[2] = add("l_P_min", g.l_P_min, "mm", kA12, "unstrained protractor length");
      j.geom[3] = add("l_R_min", g.l_R_min, "mm", kA12, "unstrained retractor length");
      break;
    }
  }
  JointTable t = joint_table(leg, type, thc_set);
  JointNaming n = joint_naming(type);
  std::string src = t.source;
  j.inertia = add("inertia", t.inertia_gmm2, "g*mm^2", src,
                  type == JointType::Fti ? "moment of inertia of the tibia" : "effective moment of inertia of the femur (2.82)",
                  1e-9);
  j.b_v = add("b_v", t.b_v_gs, "g/s", src, "muscle viscosity of the joint's muscle pair", kMinViscosityGs);
  j.k_inc_in_inc = add(std::string(n.k_inc) + "." + n.phase_inc, t.k_inc_in_inc, "mN/mm^2", src,
                       std::string(n.muscle_inc) + " spring constant during " + n.phase_inc);
  j.k_dec_in_inc = add(std::string(n.k_dec) + "." + n.phase_inc, t.k_dec_in_inc, "mN/mm^2", src,
                       std::string(n.muscle_dec) + " spring constant during " + n.phase_inc);
  j.k_inc_in_dec = add(std::string(n.k_inc) + "." + n.phase_dec, t.k_inc_in_dec, "mN/mm^2", src,
                       std::string(n.muscle_inc) + " spring constant during " + n.phase_dec);
  j.k_dec_in_dec = add(std::string(n.k_dec) + "." + n.phase_dec, t.k_dec_in_dec, "mN/mm^2", src,
                       std::string(n.muscle_dec) + " spring constant during " + n.phase_dec);
  j.angle_min = add(std::string(n.angle) + "_min", t.angle_min_deg, "deg", src, "extremal angle (target)", -180, 180);
  j.angle_max = add(std::string(n.angle) + "_max", t.angle_max_deg, "deg", src, "extremal angle (target)", -180, 180);
  return j;
}

double spring_constant_ratio(JointType type, double angle_deg) {
  double a = angle_deg * units::kRadPerDeg;
  switch (type) {
    case JointType::Fti: return fti_ratio(fti_geometry(), a);
    case JointType::Ctr: return ctr_ratio(ctr_geometry(), a);
    case JointType::Thc: return thc_ratio(thc_geometry(), a);
  }
  return NAN;
}

}  // namespace phasmid::model
