// SimRoach2 components built from a phasmid config and from the supplement's tables.
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "config/simroach2_section.hpp"
#include "simroach2/components.hpp"

using namespace phasmid::simroach2;

TEST(SimRoach2Config, MuscleAndJointFromTables) {
  // Table 3 RF CTr extensor: 0.571 N, -27.092 mN; Table 1 extensor rest length 4.005 mm.
  const auto m = muscle_from_tables("RF CTr", "extensor");
  EXPECT_DOUBLE_EQ(m.activation.amplitude_N, 0.571);
  EXPECT_DOUBLE_EQ(m.activation.y_offset_mN, -27.092);
  EXPECT_DOUBLE_EQ(m.rest_length_m, 4.005e-3);
  EXPECT_DOUBLE_EQ(m.k_se_N_per_m, 45.0);
  EXPECT_DOUBLE_EQ(m.k_pe_N_per_m, 11.24);
  EXPECT_DOUBLE_EQ(m.b_Ns_per_m, 0.1);
  // Table 2 LM FTi: 289.236 N/m, 0.399 mg/s; Table 1 spring rest length 8.602 mm.
  const auto s = spring_from_tables("LM FTi");
  EXPECT_DOUBLE_EQ(s.stiffness_N_per_m, 289.236);
  EXPECT_DOUBLE_EQ(s.damping_Ns_per_m, 0.399e-6);
  EXPECT_DOUBLE_EQ(s.rest_length_m, 8.602e-3);
  EXPECT_THROW(spring_from_tables("LM XYZ"), phasmid::Error);
  EXPECT_THROW(muscle_from_tables("LM FTi", "depressor"), phasmid::Error);
}

TEST(SimRoach2Config, ComponentsFromToml) {
  const std::string text = R"(
model = "other"
[fit]
ignored = 1
[simroach2.neuron.hc]
time_constant_ms = 5
relative_size_uS = 1
rest_potential_mV = -60
g_na_uS = 1.5
e_na_mV = 50
tau_h_max_ms = 300
m = { A = 1, S = -0.2, E = -40 }
h = { A = 0.5, S = 0.1, E = -60 }
[simroach2.synapse.p]
g_max_uS = 1.354
e_lo_mV = -60
e_hi_mV = -40
e_rev_mV = -20
[simroach2.muscle.lf_thc2_flx]
joint = "LF ThC2"
muscle = "flexor"
b_Ns_per_m = 0.2
[simroach2.joint.lf_thc2]
joint = "LF ThC2"
)";
  const auto c = phasmid::config::parse_simroach2_components(text, "x.toml");
  EXPECT_NEAR(tau_h_ms(c.neurons.at("hc"), -60.0), 141.4213562373095, 1e-9);
  EXPECT_DOUBLE_EQ(conductance_uS(c.synapses.at("p"), -50.0), 0.677);
  EXPECT_DOUBLE_EQ(c.muscles.at("lf_thc2_flx").activation.amplitude_N, 1.456);
  EXPECT_DOUBLE_EQ(c.muscles.at("lf_thc2_flx").b_Ns_per_m, 0.2);
  EXPECT_DOUBLE_EQ(c.joints.at("lf_thc2").stiffness_N_per_m, 1009.9);
}

TEST(SimRoach2Config, UnknownKeyNamesFileLineAndKey) {
  const std::string text = "[simroach2.synapse.p]\ng_max_uS = 1\ne_lo_mV = -60\ne_hi_mV = -40\ngmax = 3\n";
  try {
    phasmid::config::parse_simroach2_components(text, "y.toml");
    FAIL();
  } catch (const phasmid::Error& e) {
    EXPECT_NE(std::string(e.what()).find("y.toml:5"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("simroach2.synapse.p.gmax"), std::string::npos) << e.what();
  }
}
