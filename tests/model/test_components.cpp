// Components against hand-computed values: gating functions, steady states, forces.
#include <gtest/gtest.h>

#include <cmath>

#include "model/mechanics.hpp"
#include "model/neurons.hpp"

using namespace phasmid::model;

TEST(Neurons, BoltzmannMidpointAndSlope) {
  EXPECT_DOUBLE_EQ(boltzmann(-37.0, -37.0, -1.0 / 6), 0.5);
  // m_inf(-31) = 1/(1+exp(-1)) = 0.7310585786
  EXPECT_NEAR(boltzmann(-31.0, -37.0, -1.0 / 6), 0.7310585786, 1e-10);
  // corrected h_inf decreases with V
  EXPECT_LT(boltzmann(-20.0, -44.0, 1.0 / 6), boltzmann(-60.0, -44.0, 1.0 / 6));
}

TEST(Neurons, NapNeuronRestingBalance) {
  // With g_NaP = 0 the fixed point of V is the conductance-weighted mean of reversals:
  // V* = (g_L E_L + g_app E_app)/(g_L + g_app) = (2.8*(-65) + 0.2*0)/3.0 = -60.6667 mV.
  NapNeuronParams<double> q{1.0, 0.01, 0.0, 50, -37, -1.0 / 6, -44, 1.0 / 6, -30, -1.0 / 12, 2.8, -65, 0.2, 0};
  double dV, dh, V = (2.8 * -65.0) / 3.0;
  nap_neuron_rhs(q, V, 0.5, 0.0, dV, dh);
  EXPECT_NEAR(dV, 0.0, 1e-12);
  // dh/dt = eps (h_inf - h) cosh(gamma_tau (V - V_tau)) by hand:
  double h_inf = 1.0 / (1.0 + std::exp((V + 44.0) / 6.0));
  EXPECT_NEAR(dh, 0.01 * (h_inf - 0.5) * std::cosh(-(V + 30.0) / 12.0), 1e-14);
}

TEST(Neurons, TraubRatesAtKnownVoltage) {
  // alpha_m(V) = 0.32(-51.9-V)/(exp(0.25(-51.9-V))-1) at V = -60: x = 8.1
  double x = 8.1;
  EXPECT_NEAR(0.32 * exprel_ratio(x, 0.25), 0.32 * 8.1 / (std::exp(2.025) - 1.0), 1e-12);
  // removable singularity: x/(exp(cx)-1) -> 1/c
  EXPECT_NEAR(exprel_ratio(0.0, 0.25), 4.0, 1e-12);
  EXPECT_NEAR(exprel_ratio(1e-9, 0.25), 4.0, 1e-8);
}

TEST(Neurons, MotoneuronGateSteadyStatesAreFixedPoints) {
  MotoneuronParams<double> q{1.0, 10, 55, 0.32, -51.9, 0.25, -0.28, -24.9, -0.20, 0.128, -48, 0.056, 4.0, -25, 0.20,
                             2, -80, 0.016, -29.9, 0.20, 0.25, -45, 0.025, 12, -80, -30, -0.6, 0.0005, 0.8, -70, 0.4, 0};
  double V = -65;
  double am = 0.32 * (-51.9 - V) / (std::exp(0.25 * (-51.9 - V)) - 1), bm = 0.28 * (V + 24.9) / (std::exp(0.2 * (V + 24.9)) - 1);
  double ah = 0.128 * std::exp(0.056 * (-48 - V)), bh = 4.0 / (std::exp(0.2 * (-25 - V)) + 1);
  double ak = 0.016 * (-29.9 - V) / (std::exp(0.2 * (-29.9 - V)) - 1), bk = 0.25 * std::exp(0.025 * (-45 - V));
  double mq = 1.0 / (1.0 + std::exp(-0.6 * (V + 30)));
  double s[5] = {V, am / (am + bm), ah / (ah + bh), ak / (ak + bk), mq}, ds[5];
  motoneuron_rhs(q, s, 0.0, ds);
  for (int i = 1; i < 5; ++i) EXPECT_NEAR(ds[i], 0.0, 1e-12) << "gate " << i;
}

TEST(Mechanics, FtiFibreLengthAt90DegIsReference) {
  FtiGeometry<double> g{0.28, 1.41, 2.11, 1.05, 1.50, 0.34, 0.42};
  double l, c;
  fibre(g.l_E0, g.h_E, g.d * std::cos(M_PI / 2), l, c);
  EXPECT_NEAR(l, 1.41, 1e-12);
  EXPECT_NEAR(c, std::sqrt(1 - std::pow(0.34 / 1.41, 2)), 1e-12);
}

TEST(Mechanics, ForceLawAndCtrBalance) {
  EXPECT_DOUBLE_EQ(muscle_force(510.0, 1.25, 1.05), 510.0 * 0.2 * 0.2);
  // CTr at beta with k_D/k_L = a_LD(beta) is stationary (2.44).
  CtrGeometry<double> g{3.5, 1.0, 1.05, 1.5};
  double beta = 45 * M_PI / 180, kL = 1000.0, kD = kL * ctr_ratio(g, beta);
  EXPECT_NEAR(ctr_acceleration(g, 0.9341, 84.0, beta, 0.0, kL, kD), 0.0, 1e-9);
}

TEST(Mechanics, ThcAndFtiStationaryAtRatio) {
  ThcGeometry<double> t{2.0, 2.5, 1.0, 1.5};
  double a = 100 * M_PI / 180, kP = 300.0;
  EXPECT_NEAR(thc_acceleration(t, 0.9341, 25.5, a, 0.0, kP, kP * thc_ratio(t, a)), 0.0, 1e-9);
  FtiGeometry<double> f{0.28, 1.41, 2.11, 1.05, 1.50, 0.34, 0.42};
  double gmm = 80 * M_PI / 180, kE = 510.0;
  EXPECT_NEAR(fti_acceleration(f, 0.1008, 12.5, gmm, 0.0, kE, kE * fti_ratio(f, gmm)), 0.0, 1e-9);
}

TEST(Mechanics, EffectiveInertiaTableA15) {
  // (2.82) with Table A.13 middle-leg segments and gamma in [45, 110] deg gives Table A.15's 0.9341 g mm^2,
  // and the tibia alone I_T = M L^2 / 3 gives Table A.14's 0.1008.
  EXPECT_NEAR(effective_femur_inertia(0.0073, 13, 0.0021, 12, 45 * M_PI / 180, 110 * M_PI / 180), 0.9341, 5e-5);
  EXPECT_NEAR(rod_inertia(0.0021, 12), 0.1008, 1e-12);
  EXPECT_NEAR(rod_inertia(0.0039, 16), 0.3328, 1e-12);  // Table A.18
}
