// SimRoach2 components against hand-computed values (supplement eqs. 1-8, 5, 15-20, Sect. 2.3).
#include <gtest/gtest.h>

#include <cmath>

#include "common/error.hpp"
#include "simroach2/muscle.hpp"
#include "simroach2/neuron.hpp"
#include "simroach2/passive_joint.hpp"
#include "simroach2/synapse.hpp"

using namespace phasmid::simroach2;

namespace {
NeuronParameters passive_neuron() {
  NeuronParameters p;
  p.time_constant_ms = 5.0;   // C_m = 5 nF with G_m = 1 uS
  p.relative_size_uS = 1.0;
  p.rest_potential_mV = -60.0;
  return p;
}
}  // namespace

// Eq. (9): C dV/dt = G (E_r - V): 5 nF dV/dt = 1 uS (-60 + 50) mV -> -2 mV/ms.
TEST(SimRoach2Neuron, LeakOnly) {
  const auto p = passive_neuron();
  EXPECT_DOUBLE_EQ(p.capacitance_nF(), 5.0);
  EXPECT_DOUBLE_EQ(dV_dt(p, -50.0, 0.0, 0.0, 0.0), -2.0);
  EXPECT_DOUBLE_EQ(dV_dt(p, -60.0, 0.0, 0.0, 3.0), 0.6);  // 3 nA / 5 nF
  EXPECT_DOUBLE_EQ(dh_dt(p, -50.0, 0.3), 0.0);             // no NaP channel
}

// Eq. (5): G = 2 uS * (-45 + 60) / (-40 + 60) = 1.5 uS; I = 1.5 * (-20 + 50) = 45 nA;
// dV/dt = (-10 + 45) / 5 = 7 mV/ms.
TEST(SimRoach2Synapse, PiecewiseLinearConductanceAndCurrent) {
  const SynapseParameters s{2.0, -60.0, -40.0, -20.0};
  EXPECT_DOUBLE_EQ(conductance_uS(s, -45.0), 1.5);
  EXPECT_DOUBLE_EQ(conductance_uS(s, -70.0), 0.0);  // below E_lo
  EXPECT_DOUBLE_EQ(conductance_uS(s, -30.0), 2.0);  // saturated above E_hi
  EXPECT_DOUBLE_EQ(current_nA(s, -45.0, -50.0), 45.0);
  EXPECT_DOUBLE_EQ(dV_dt(passive_neuron(), -50.0, 0.0, current_nA(s, -45.0, -50.0), 0.0), 7.0);
}

// Eqs. (4), (6)-(8) with m: A 1, S -0.2/mV, E -40 mV; h: A 0.5, S 0.1/mV, E -60 mV;
// tau_h,max 300 ms; G_Na 1.5 uS; E_Na 50 mV.
TEST(SimRoach2Neuron, PersistentSodium) {
  auto p = passive_neuron();
  p.g_na_uS = 1.5;
  p.e_na_mV = 50.0;
  p.m = {1.0, -0.2, -40.0};
  p.h = {0.5, 0.1, -60.0};
  p.tau_h_max_ms = 300.0;
  EXPECT_DOUBLE_EQ(p.m(-40.0), 0.5);
  EXPECT_NEAR(p.h(-60.0), 2.0 / 3.0, 1e-15);
  // 300 * (2/3) * sqrt(0.5) = 141.4213562 ms
  EXPECT_NEAR(tau_h_ms(p, -60.0), 141.4213562373095, 1e-9);
  // 1.5 * 0.5 * 0.5 * (50 + 40) = 33.75 nA
  EXPECT_NEAR(i_nap_nA(p, -40.0, 0.5), 33.75, 1e-12);
  // (2/3 - 0.2) / 141.42 = 0.0032998 1/ms
  EXPECT_NEAR(dh_dt(p, -60.0, 0.2), (2.0 / 3.0 - 0.2) / 141.4213562373095, 1e-15);
  // Leak 1 * (-60 + 40) = -20 nA plus 33.75 nA -> 13.75 / 5 = 2.75 mV/ms.
  EXPECT_NEAR(dV_dt(p, -40.0, 0.5, 0.0, 0.0), 2.75, 1e-12);
  // h_inf decreases with V (inactivation).
  EXPECT_LT(p.h(-40.0), p.h(-60.0));
}

// Sect. 2.3: x-offset -50 mV, steepness 300 (per volt); Fig. 13 example amplitude 1 N.
TEST(SimRoach2Muscle, ActivationCurve) {
  ActivationCurve c;
  c.amplitude_N = 1.0;
  EXPECT_DOUBLE_EQ(c.force_N(-50.0), 0.5);
  EXPECT_NEAR(c.force_N(-60.0), 1.0 / (1.0 + std::exp(3.0)), 1e-15);  // 0.0474259 N
  EXPECT_NEAR(c.force_N(-40.0), 1.0 / (1.0 + std::exp(-3.0)), 1e-15);
  // Table 3, LF ThC2 flexor: 1456 mN * 0.0474259 - 69.036 mN = +0.0161 mN at -60 mV.
  c.amplitude_N = 1.456;
  c.y_offset_mN = -69.036;
  EXPECT_NEAR(1e3 * c.force_N(-60.0), 0.016071, 1e-6);
}

// dT/dt = k_se/b (k_pe dx + b v - (1 + k_pe/k_se) T + A) with Sect. 2.3's k_se 45, k_pe 11.24,
// b 0.1; x_rest 4.217 mm (Table 1, LF ThC2 flexor), stretch 1 mm, v 0.01 m/s, T 0.2 N, A 0.5 N:
// 450 * (0.01124 + 0.001 - 1.2497778 * 0.2 + 0.5) = 118.028 N/s.
TEST(SimRoach2Muscle, HillTensionRate) {
  MuscleParameters m;
  m.rest_length_m = 4.217e-3;
  EXPECT_NEAR(tension_rate_N_per_s(m, 0.2, 5.217e-3, 0.01, 0.5), 118.028, 1e-3);
  EXPECT_NEAR(tension_rate_N_per_s(m, 0.2, 5.217e-3, 0.01, 0.5), 450.0 * (0.01124 + 0.001 - (1.0 + 11.24 / 45.0) * 0.2 + 0.5), 1e-10);
  // Isometric at rest length with A = 1 N: 45 / 56.24 = 0.800142 N.
  EXPECT_NEAR(isometric_tension_N(m, m.rest_length_m, 1.0), 0.8001422475, 1e-9);
  // Integrating the tension ODE at fixed length reaches that steady state (time constant
  // b / (k_se + k_pe) = 1.78 ms; 50 ms of explicit Euler at 1 us).
  double T = 0.0;
  for (int i = 0; i < 50000; ++i) T += 1e-6 * tension_rate_N_per_s(m, T, m.rest_length_m, 0.0, 1.0);
  EXPECT_NEAR(T, 0.8001422475, 1e-9);
}

// Table 2, LF ThC2: k = 1009.9 N/m, c = 2.414 mg/s = 2.414e-6 N s/m.
TEST(SimRoach2PassiveJoint, SpringDamperForce) {
  PassiveSpringDamper s{1009.9, 2.414 * kNsPerM_per_mgPerS, 4.217e-3};
  EXPECT_NEAR(s.force_N(4.317e-3, 0.0), 0.10099, 1e-12);
  EXPECT_NEAR(s.force_N(4.217e-3, 0.01), 2.414e-8, 1e-20);
}

// Eqs. (15)-(20) at a = r = 1 mm, theta = 90 deg: L = sqrt(2) mm, sin(alpha) = 1/sqrt(2);
// k = 100 N/m, I = 1e-9 kg m^2: k_t = 100 * 1e-6 * 0.5 = 5e-5 N m/rad; omega_n = 223.607 rad/s;
// c_t = 2 * 223.607 * 1e-9 = 4.47214e-7 N m s; c = c_t / (1e-6 * 0.5) = 0.894427 N s/m.
TEST(SimRoach2Design, CriticalDampingEquations) {
  const SpringGeometry g{1e-3, 1e-3};
  const double theta = M_PI / 2;
  EXPECT_NEAR(g.spring_length_m(theta), std::sqrt(2.0) * 1e-3, 1e-15);
  EXPECT_NEAR(std::sin(g.alpha_rad(theta)), 1.0 / std::sqrt(2.0), 1e-12);
  const double kt = equivalent_torsional_stiffness(100.0, 1e-3, g.alpha_rad(theta));
  EXPECT_NEAR(kt, 5e-5, 1e-17);
  EXPECT_NEAR(natural_frequency_rad_per_s(kt, 1e-9), 223.60679775, 1e-7);
  const double ct = torsional_damping(kt, 1e-9);
  EXPECT_NEAR(ct, 4.4721359550e-7, 1e-16);
  EXPECT_NEAR(linear_damping_from_torsional(ct, 1e-3, g.alpha_rad(theta)), 0.894427191, 1e-9);
  EXPECT_THROW(linear_damping_from_torsional(ct, 1e-3, 0.0), phasmid::Error);
}

// Over 60..120 deg the spring is least perpendicular at 120 deg: L = sqrt(3) mm,
// sin(alpha) = sin(120) / sqrt(3) = 0.5, c = 2 sqrt(k I) / (r sin(alpha)) = 1.264911 N s/m.
TEST(SimRoach2Design, LargestCriticalDampingOverTheRange) {
  const SpringGeometry g{1e-3, 1e-3};
  const auto d = critical_damping_over_range(100.0, 1e-9, g, M_PI / 3, 2 * M_PI / 3, 61);
  EXPECT_NEAR(d.theta_at_max_rad, 2 * M_PI / 3, 1e-12);
  EXPECT_NEAR(d.c_max_Ns_per_m, 2.0 * std::sqrt(100.0 * 1e-9) / (1e-3 * 0.5), 1e-9);
  EXPECT_NEAR(d.c[30], 0.894427191, 1e-9);  // 90 deg
  // 60 deg: L = 1 mm, sin(alpha) = 0.866 -> 0.730297 N s/m, the smallest.
  EXPECT_NEAR(d.c.front(), 2.0 * std::sqrt(1e-7) / (1e-3 * std::sqrt(3.0) / 2), 1e-9);
}
