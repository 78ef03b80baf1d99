#pragma once
// The [simroach2] section of a TOML text: SimRoach2 components (simroach2/components.hpp).
//
//   [simroach2.neuron.<name>]   time_constant_ms, relative_size_uS, rest_potential_mV,
//                               g_na_uS, e_na_mV, tau_h_max_ms, m = {A, S, E}, h = {A, S, E}
//   [simroach2.synapse.<name>]  g_max_uS, e_lo_mV, e_hi_mV, e_rev_mV
//   [simroach2.muscle.<name>]   joint = "LF ThC2", muscle = "flexor" | "extensor" (Tables 1, 3),
//                               optional k_se_N_per_m, k_pe_N_per_m, b_Ns_per_m, amplitude_N,
//                               y_offset_mN, x_offset_mV, steepness_per_V, rest_length_mm
//   [simroach2.joint.<name>]    joint = "LF ThC2" (Tables 1, 2), optional stiffness_N_per_m,
//                               damping_mg_per_s, rest_length_mm
// Unknown keys are errors naming file, line and key.
#include <string>

#include "simroach2/components.hpp"

namespace phasmid::config {

// Reads the [simroach2] section of a TOML text (other sections are ignored).
simroach2::Components parse_simroach2_components(const std::string& text, const std::string& origin);

}  // namespace phasmid::config
