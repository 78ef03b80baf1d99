#include "model/mechanical_joint_model.hpp"

#include <cmath>

#include "common/units.hpp"

namespace phasmid::model {

std::unique_ptr<MechanicalJointModel> MechanicalJointModel::section311(const std::string& leg, JointType joint,
                                                                      bool start_inc, const std::string& thc_set) {
  const double period_ms = 500;
  const double inc_ms = joint == JointType::Fti ? 250 : joint == JointType::Ctr ? 188 : 125;
  const JointTable t = joint_table(leg, joint, thc_set);
  return std::make_unique<MechanicalJointModel>(leg, joint, start_inc, start_inc ? inc_ms : period_ms - inc_ms,
                                                period_ms, start_inc ? t.angle_min_deg : t.angle_max_deg, thc_set);
}

MechanicalJointModel::MechanicalJointModel(const std::string& leg, JointType joint, bool start_inc,
                                           double first_phase_ms, double period_ms, double angle0_deg,
                                           const std::string& thc_set)
    : start_inc_(start_inc) {
  joint_ = define_joint_mechanics(params_, leg, joint, thc_set);
  JointNaming n = joint_naming(joint);
  const std::string pre = joint_.prefix + ".";
  const char* s31 = "Knops 2013, Section 3.1.1";
  period_ = params_.add({pre + "switch.period_ms", period_ms, "ms", s31, "period of the prescribed switching", 1e-3, INFINITY});
  first_phase_ = params_.add({pre + "switch.first_phase_ms", first_phase_ms, "ms", s31,
                              "duration of the first phase of each period", 0.0, INFINITY});
  angle0_ = params_.add({pre + n.angle + "0", angle0_deg, "deg", s31, "initial angle (at rest)", -180, 180});
  size_t a = add_state(pre + n.angle, "rad");
  size_t w = add_state(pre + n.angle + "_dot", "rad/s");
  angles_.push_back({leg, joint_name(joint), a, w});
}

std::vector<double> MechanicalJointModel::initial_state(const std::vector<double>& p) const {
  return {units::deg_to_rad(p[angle0_]), 0.0};
}

std::vector<double> MechanicalJointModel::breakpoints(const std::vector<double>& p, double t_end) const {
  std::vector<double> b;
  for (double t0 = 0.0; t0 < t_end; t0 += p[period_]) {
    if (t0 > 0) b.push_back(t0);
    if (t0 + p[first_phase_] < t_end && p[first_phase_] > 0) b.push_back(t0 + p[first_phase_]);
  }
  return b;
}

}  // namespace phasmid::model
