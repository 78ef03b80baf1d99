#pragma once
// Joint mechanics of Knops (2013) Section 2.3, templated on the scalar type.
// Units at this level are the dissertation's (docs/model.md "Units"): spring constants in mN/mm^2,
// lengths in mm, inertia in g*mm^2, viscosity in g/s, angles in rad, and time in SECONDS
// (the tables are consistent with inserting these numbers directly into (2.22), (2.34),
// (2.41)). Callers working in ms convert at their boundary.
#include <cmath>

namespace phasmid::model {

enum class JointType { Thc, Ctr, Fti };

// Quadratic muscle force law (2.19): F = k (l - l_min)^2.
template <class T, class P>
T muscle_force(const T& k, const T& l, const P& l_min) {
  T stretch = l - l_min;
  return k * stretch * stretch;
}

// ---- FTi joint (flexor/extensor), eqs. (2.20)-(2.28) ------------------------------------
template <class P>
struct FtiGeometry {
  P d;                    // tendon lever of the extensor; the flexor's is 2d (mm), Table A.10
  P l_E0, l_F0;           // fibre lengths at gamma = 90 deg (mm)
  P l_E_min, l_F_min;     // unstrained fibre lengths (mm)
  P h_E, h_F;             // tendon-cuticle distances (mm)
};

// Fibre length and cos(fibre-tendon angle) for a tendon shift s (2.27)/(2.28). The shift is
// s_F = -2d cos(gamma), s_E = d cos(gamma): the printed sine contradicts l_0 being the length
// at 90 deg and does not reproduce Section 3.1's ratios (docs/model.md "Muscles and joints").
template <class T, class P>
void fibre(const P& l0, const P& h, const T& shift, T& length, T& cos_phi) {
  using std::sqrt;
  P cos_phi0 = sqrt(1.0 - (h / l0) * (h / l0));
  length = sqrt(l0 * l0 + shift * shift - 2.0 * l0 * shift * cos_phi0);
  cos_phi = sqrt(1.0 - (h / length) * (h / length));
}

struct FtiMuscleState {};

// Parallel (tendon-direction) forces of flexor and extensor at angle gamma (rad), (2.23)-(2.26).
template <class T, class P>
void fti_tendon_forces(const FtiGeometry<P>& g, const T& gamma, const T& k_E, const T& k_F, T& F_pE, T& F_pF) {
  using std::cos;
  T lE, cE, lF, cF;
  fibre(g.l_E0, g.h_E, T(g.d * cos(gamma)), lE, cE);
  fibre(g.l_F0, g.h_F, T(-2.0 * g.d * cos(gamma)), lF, cF);
  F_pE = muscle_force(k_E, lE, g.l_E_min) * cE;
  F_pF = muscle_force(k_F, lF, g.l_F_min) * cF;
}

// Angular acceleration of the tibia (2.22), rad/s^2.
template <class T, class P>
T fti_acceleration(const FtiGeometry<P>& g, const P& inertia, const P& b_v, const T& gamma, const T& omega,
                   const T& k_E, const T& k_F) {
  using std::sin;
  T F_pE, F_pF;
  fti_tendon_forces(g, gamma, k_E, k_F, F_pE, F_pF);
  return g.d / inertia * ((2.0 * F_pF - F_pE) * sin(gamma) - 5.0 * b_v * g.d * omega);
}

// Spring-constant ratio a_FE = k_F / k_E at a stationary extremal angle (2.43).
template <class T, class P>
T fti_ratio(const FtiGeometry<P>& g, const T& gamma_e) {
  using std::cos;
  T lE, cE, lF, cF;
  fibre(g.l_E0, g.h_E, T(g.d * cos(gamma_e)), lE, cE);
  fibre(g.l_F0, g.h_F, T(-2.0 * g.d * cos(gamma_e)), lF, cF);
  T sE = lE - g.l_E_min, sF = lF - g.l_F_min;
  return 0.5 * (sE * sE * cE) / (sF * sF * cF);
}

// ---- CTr joint (levator/depressor), eqs. (2.29)-(2.34) ----------------------------------
template <class P>
struct CtrGeometry {
  P d, r;              // distance AB and radius (mm), Table A.11
  P l_L_min, l_D_min;  // unstrained lengths (mm)
};

template <class T, class P>
T ctr_acceleration(const CtrGeometry<P>& g, const P& inertia, const P& b_v, const T& beta, const T& omega,
                   const T& k_L, const T& k_D) {
  T F_L = muscle_force(k_L, T(g.d - g.r * beta), g.l_L_min);  // (2.29), (2.32)
  T F_D = muscle_force(k_D, T(g.d + g.r * beta), g.l_D_min);  // (2.30), (2.33)
  return g.r / inertia * (F_L - F_D) - b_v * g.r * g.r / inertia * omega;  // (2.34)
}

// a_LD = k_D / k_L at a stationary extremal angle (2.44).
template <class T, class P>
T ctr_ratio(const CtrGeometry<P>& g, const T& beta_e) {
  T q = (g.d - g.r * beta_e - g.l_L_min) / (g.d + g.r * beta_e - g.l_D_min);
  return q * q;
}

// ---- ThC joint (protractor/retractor), eqs. (2.35)-(2.41) -------------------------------
template <class P>
struct ThcGeometry {
  P d, r;              // insertion distance on the femur and on the thorax (mm), Table A.12
  P l_P_min, l_R_min;  // unstrained lengths (mm)
};

template <class T, class P>
void thc_lengths(const ThcGeometry<P>& g, const T& alpha, T& l_P, T& l_R) {
  using std::cos;
  using std::sqrt;
  l_R = sqrt(g.r * g.r + g.d * g.d + 2.0 * g.r * g.d * cos(alpha));  // (2.39)
  l_P = sqrt(g.r * g.r + g.d * g.d - 2.0 * g.r * g.d * cos(alpha));  // (2.40)
}

template <class T, class P>
T thc_acceleration(const ThcGeometry<P>& g, const P& inertia, const P& b_v, const T& alpha, const T& omega,
                   const T& k_P, const T& k_R) {
  using std::sin;
  T l_P, l_R;
  thc_lengths(g, alpha, l_P, l_R);
  T F_P = muscle_force(k_P, l_P, g.l_P_min);
  T F_R = muscle_force(k_R, l_R, g.l_R_min);
  return g.r * g.d / inertia * sin(alpha) * (F_R / l_R - F_P / l_P) - b_v * g.d * g.d / inertia * omega;  // (2.41)
}

// a_PR = k_R / k_P at a stationary extremal angle (2.45).
template <class T, class P>
T thc_ratio(const ThcGeometry<P>& g, const T& alpha_e) {
  T l_P, l_R;
  thc_lengths(g, alpha_e, l_P, l_R);
  T sP = l_P - g.l_P_min, sR = l_R - g.l_R_min;
  return l_R * sP * sP / (l_P * sR * sR);
}

// ---- Femur-tibia inertia, eqs. (2.80)-(2.82) --------------------------------------------
// Effective moment of inertia of the femur with the tibia attached, averaged over the FTi
// range [gamma_min, gamma_max] (rad); masses in g, lengths in mm, result in g*mm^2.
inline double effective_femur_inertia(double M_F, double L_F, double M_T, double L_T, double gamma_min,
                                      double gamma_max) {
  double I_F = M_F * L_F * L_F / 3.0, I_T = M_T * L_T * L_T / 3.0;
  return I_F + I_T + M_T * L_F * L_F +
         M_T * L_T * L_F * (std::sin(gamma_max) - std::sin(gamma_min)) / (gamma_max - gamma_min);
}

inline double rod_inertia(double mass_g, double length_mm) { return mass_g * length_mm * length_mm / 3.0; }

// ---- any joint ----------------------------------------------------------------------------
// Angular acceleration (rad/s^2) of a joint of the given type from its geometry parameters g
// (define_joint_mechanics' order; CTr and ThC read the first four), inertia, viscosity, angle
// (rad), omega (rad/s) and the spring constants of the angle-increasing and -decreasing muscle.
// Generic evaluations (model/joint.hpp) and compiled ones (model/network_codegen.cpp) both call
// it, so that they compute the same numbers.
template <class T, class P>
T joint_type_acceleration(JointType type, const P* const* g, const P& inertia, const P& b_v, const T& angle,
                          const T& omega, const T& k_inc, const T& k_dec) {
  switch (type) {
    case JointType::Fti: {
      FtiGeometry<P> geo{*g[0], *g[1], *g[2], *g[3], *g[4], *g[5], *g[6]};
      return fti_acceleration(geo, inertia, b_v, angle, omega, k_dec, k_inc);
    }
    case JointType::Ctr: {
      CtrGeometry<P> geo{*g[0], *g[1], *g[2], *g[3]};
      return ctr_acceleration(geo, inertia, b_v, angle, omega, k_inc, k_dec);
    }
    case JointType::Thc: {
      ThcGeometry<P> geo{*g[0], *g[1], *g[2], *g[3]};
      return thc_acceleration(geo, inertia, b_v, angle, omega, k_dec, k_inc);
    }
  }
  return T(0.0);
}

}  // namespace phasmid::model
