#pragma once
// Section 3.1.1: a single joint driven by mechanics only. The spring constants switch
// between the two phases at prescribed times (no neurons), e.g. FTi flexion for 250 ms and
// extension for 250 ms (period 500 ms, 1:1), starting at rest at gamma = 45 deg.
#include <memory>

#include "model/joint.hpp"
#include "model/leg_tables.hpp"
#include "model/ode_model.hpp"

namespace phasmid::model {

class MechanicalJointModel : public OdeModelT<MechanicalJointModel> {
 public:
  // start_inc: whether the first phase is the angle-increasing one (flexion, levation, retraction).
  MechanicalJointModel(const std::string& leg, JointType joint, bool start_inc, double first_phase_ms,
                       double period_ms, double angle0_deg, const std::string& thc_set = "");
  // The Section 3.1.1 set-up: period 500 ms; phase relations FE 1:1, PR 1:3 (retraction
  // 125 ms), LD 3:5 (levation 188 ms); the joint starts at rest at the extremal angle of its
  // first phase (the angle-increasing one if start_inc).
  static std::unique_ptr<MechanicalJointModel> section311(const std::string& leg, JointType joint, bool start_inc,
                                                          const std::string& thc_set = "");
  std::string kind() const override { return "mechanical_joint"; }
  const JointMechanics& joint() const { return joint_; }
  bool starts_inc() const { return start_inc_; }

  std::vector<double> initial_state(const std::vector<double>& p) const override;
  std::vector<double> breakpoints(const std::vector<double>& p, double t_end) const override;

  // True while the angle-increasing muscle is the active one at time t (ms).
  template <class T>
  bool in_inc_phase(double t, const T* p) const {
    double period = value_of(p[period_]), first = value_of(p[first_phase_]);
    double phase = std::fmod(t, period);
    bool first_phase = phase < first;
    return first_phase == start_inc_;
  }

  template <class T>
  void eval(double t, const T* y, const T* p, T* ydot) const {
    bool inc = in_inc_phase(t, p);
    const T& k_inc = inc ? p[joint_.k_inc_in_inc] : p[joint_.k_inc_in_dec];
    const T& k_dec = inc ? p[joint_.k_dec_in_inc] : p[joint_.k_dec_in_dec];
    ydot[0] = y[1] * 1e-3;  // rad/s -> rad/ms
    ydot[1] = joint_acceleration(joint_, p, y[0], y[1], k_inc, k_dec) * 1e-3;  // rad/s^2 -> (rad/s)/ms
  }

 private:
  JointMechanics joint_;
  bool start_inc_;
  size_t period_, first_phase_, angle0_;
};

}  // namespace phasmid::model
