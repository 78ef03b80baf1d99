#pragma once
// Knops (2013) Section 2.4 / Appendix B: the mechanically coupled femur-tibia system (a double
// pendulum in the CTr-FTi plane), eqs. (2.46)-(2.79), driven by the prescribed phase-wise
// spring constants of Section 3.1 (CTr levation 188 ms / depression 312 ms, FTi flexion 250 ms /
// extension 250 ms, period 500 ms). States beta, beta_dot, gamma, gamma_dot.
//
// With M = [[A, -B], [-B, I_T]] the Euler-Lagrange equations (2.73)/(2.74) read
//   M [beta_dd, gamma_dd] = [Q_beta + C (2 beta_d - gamma_d) gamma_d, Q_gamma - C beta_d^2]
// A = I_F + I_T + M_T L_F^2 + M_T L_T L_F cos g, B = I_T + M_T L_T L_F cos(g)/2,
// C = M_T L_F L_T sin(g)/2. The generalized forces are the isolated joints' muscle and viscous
// torques, Q_beta = r (F_L - F_D) - b_LD r^2 beta_d (2.31) and
// Q_gamma = d (2 F_pF - F_pE) sin g - 5 b_FE d^2 gamma_d (2.20)-(2.21), so that for a fixed
// femur the FTi equation is (2.22) and for an averaged A the CTr equation is (2.34)/(2.82).
// (The printed (2.69)/(2.70) write Q = +F dl/dq, which for a contracting muscle has the wrong
// sign against (2.31); docs/model.md.)
#include "model/joint.hpp"
#include "model/ode_model.hpp"

namespace phasmid::model {

class CoupledCtrFtiModel : public OdeModelT<CoupledCtrFtiModel> {
 public:
  explicit CoupledCtrFtiModel(const std::string& leg = "middle");
  std::string kind() const override { return "coupled_ctr_fti"; }
  std::vector<double> initial_state(const std::vector<double>& p) const override;
  std::vector<double> breakpoints(const std::vector<double>& p, double t_end) const override;

  // Kinetic energy (2.58) in g*mm^2/s^2 (for tests: conserved without forces).
  double kinetic_energy(const std::vector<double>& y, const std::vector<double>& p) const;

  template <class T>
  void eval(double t, const T* y, const T* p, T* ydot) const {
    using std::cos;
    using std::sin;
    const T &beta = y[0], &bd = y[1], &gam = y[2], &gd = y[3];
    bool lev = std::fmod(t, value_of(p[period_])) < value_of(p[lev_ms_]);
    bool flx = std::fmod(t, value_of(p[period_])) < value_of(p[flx_ms_]);
    const JointMechanics& c = ctr_;
    const JointMechanics& f = fti_;
    // Muscle and viscous torques of the isolated joints, as torques (inertia 1): the
    // *_acceleration functions return torque / inertia, so multiply back by the inertia.
    T k_L = lev ? p[c.k_inc_in_inc] : p[c.k_inc_in_dec], k_D = lev ? p[c.k_dec_in_inc] : p[c.k_dec_in_dec];
    T k_F = flx ? p[f.k_inc_in_inc] : p[f.k_inc_in_dec], k_E = flx ? p[f.k_dec_in_inc] : p[f.k_dec_in_dec];
    T Q_beta = joint_acceleration(c, p, beta, bd, k_L, k_D) * p[c.inertia];
    T Q_gamma = joint_acceleration(f, p, gam, gd, k_F, k_E) * p[f.inertia];
    const T &M_F = p[M_F_], &L_F = p[L_F_], &M_T = p[M_T_], &L_T = p[L_T_];
    T I_F = M_F * L_F * L_F / 3.0, I_T = M_T * L_T * L_T / 3.0;
    T A = I_F + I_T + M_T * L_F * L_F + M_T * L_T * L_F * cos(gam);
    T B = I_T + 0.5 * M_T * L_T * L_F * cos(gam);
    T C = 0.5 * M_T * L_F * L_T * sin(gam);
    T r1 = Q_beta + C * (2.0 * bd - gd) * gd;
    T r2 = Q_gamma - C * bd * bd;
    T D = A * I_T - B * B;  // determinant (2.75)
    T bdd = (I_T * r1 + B * r2) / D;
    T gdd = (B * r1 + A * r2) / D;
    ydot[0] = bd * 1e-3;
    ydot[1] = bdd * 1e-3;
    ydot[2] = gd * 1e-3;
    ydot[3] = gdd * 1e-3;
  }

 private:
  JointMechanics ctr_, fti_;
  size_t M_F_, L_F_, M_T_, L_T_, period_, lev_ms_, flx_ms_, beta0_, gamma0_;
};

}  // namespace phasmid::model
