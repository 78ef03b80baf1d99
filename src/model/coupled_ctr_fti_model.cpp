#include "model/coupled_ctr_fti_model.hpp"

#include <cmath>

#include "common/units.hpp"

namespace phasmid::model {

CoupledCtrFtiModel::CoupledCtrFtiModel(const std::string& leg) {
  ctr_ = define_joint_mechanics(params_, leg, JointType::Ctr);
  fti_ = define_joint_mechanics(params_, leg, JointType::Fti);
  SegmentTable s = segment_table(leg);
  const char* a13 = "Knops 2013, Table A.13";
  const char* b = "Knops 2013, Section 3.1.1 / Appendix B";
  const std::string pre = leg + ".";
  M_F_ = params_.add({pre + "femur.mass", s.femur_mass_g, "g", a13, "femur mass", 1e-9, INFINITY});
  L_F_ = params_.add({pre + "femur.length", s.femur_length_mm, "mm", a13, "femur length", 1e-9, INFINITY});
  M_T_ = params_.add({pre + "tibia.mass", s.tibia_mass_g, "g", a13, "tibia mass", 1e-9, INFINITY});
  L_T_ = params_.add({pre + "tibia.length", s.tibia_length_mm, "mm", a13, "tibia length", 1e-9, INFINITY});
  period_ = params_.add({pre + "coupled.switch.period_ms", 500, "ms", b, "period of the prescribed switching", 1e-3, INFINITY});
  lev_ms_ = params_.add({pre + "coupled.switch.levation_ms", 188, "ms", b, "levation phase (LD 3:5)", 0, INFINITY});
  flx_ms_ = params_.add({pre + "coupled.switch.flexion_ms", 250, "ms", b, "flexion phase (FE 1:1)", 0, INFINITY});
  beta0_ = params_.add({pre + "ctr.beta0", 30, "deg", b, "initial beta (at rest, beta_min)", -180, 180});
  gamma0_ = params_.add({pre + "fti.gamma0", 45, "deg", b, "initial gamma (at rest, gamma_min)", -180, 180});
  add_state(pre + "ctr.beta", "rad");
  add_state(pre + "ctr.beta_dot", "rad/s");
  add_state(pre + "fti.gamma", "rad");
  add_state(pre + "fti.gamma_dot", "rad/s");
  angles_.push_back({leg, "ctr", 0, 1});
  angles_.push_back({leg, "fti", 2, 3});
}

std::vector<double> CoupledCtrFtiModel::initial_state(const std::vector<double>& p) const {
  return {units::deg_to_rad(p[beta0_]), 0.0, units::deg_to_rad(p[gamma0_]), 0.0};
}

std::vector<double> CoupledCtrFtiModel::breakpoints(const std::vector<double>& p, double t_end) const {
  std::vector<double> b;
  for (double t0 = 0; t0 < t_end; t0 += p[period_])
    for (double off : {0.0, p[lev_ms_], p[flx_ms_]})
      if (t0 + off > 0 && t0 + off < t_end) b.push_back(t0 + off);
  return b;
}

double CoupledCtrFtiModel::kinetic_energy(const std::vector<double>& y, const std::vector<double>& p) const {
  double I_F = p[M_F_] * p[L_F_] * p[L_F_] / 3, I_T = p[M_T_] * p[L_T_] * p[L_T_] / 3;
  double bd = y[1], gd = y[3];
  return 0.5 * I_F * bd * bd + 0.5 * I_T * (bd - gd) * (bd - gd) + 0.5 * p[M_T_] * p[L_F_] * p[L_F_] * bd * bd +
         0.5 * p[M_T_] * p[L_F_] * p[L_T_] * bd * (bd - gd) * std::cos(y[2]);
}

}  // namespace phasmid::model
