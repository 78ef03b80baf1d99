#pragma once
// One joint's mechanics as named parameters (indices into the model's parameter vector)
// and its angular acceleration, dispatching to the FtiJoint / CtrJoint / ThcJoint equations.
#include <string>

#include "model/leg_tables.hpp"
#include "model/mechanics.hpp"
#include "model/parameters.hpp"

namespace phasmid::model {

struct JointMechanics {
  JointType type;
  std::string prefix;      // "middle.fti"
  size_t geom[7];          // geometry parameters (see define_joint_mechanics)
  size_t inertia, b_v;
  // Phase-wise spring constants: k of the inc/dec muscle during the inc/dec phase.
  size_t k_inc_in_inc, k_dec_in_inc, k_inc_in_dec, k_dec_in_dec;
  size_t angle_min, angle_max;  // extremal angles (deg), the targets of Section 3.1
};

// Defines "<leg>.<joint>.*" parameters from Tables A.10-A.23 and returns their indices.
JointMechanics define_joint_mechanics(ParameterSet& ps, const std::string& leg, JointType type,
                                      const std::string& thc_set = "");

// Angular acceleration in rad/s^2 (time in s, docs/model.md "Units") for angle (rad), omega (rad/s),
// and the current spring constants of the inc and dec muscles (mN/mm^2).
template <class T>
T joint_acceleration(const JointMechanics& j, const T* p, const T& angle, const T& omega, const T& k_inc,
                     const T& k_dec) {
  const T* g[7];
  for (int i = 0; i < 7; ++i) g[i] = &p[j.geom[i]];
  return joint_type_acceleration(j.type, g, p[j.inertia], p[j.b_v], angle, omega, k_inc, k_dec);
}

// Stationary spring-constant ratio at an extremal angle (deg), eqs. (2.43)-(2.45):
// FTi k_F/k_E, CTr k_D/k_L, ThC k_R/k_P, with the geometry of Tables A.10-A.12.
double spring_constant_ratio(JointType type, double angle_deg);

}  // namespace phasmid::model
