#pragma once
// The stiff linear part of the network's equations, for IMEX integration (solver/ark_imex_session.hpp).
// Every membrane equation is affine in its own potential given the other states,
// C dV/dt = -g_tot(y) V + I(y), and every gate's equation is affine in the gate,
// dz/dt = a(y) - kappa(y) z. stiff_rates() returns kappa_i(y) per state (1/ms): g_tot/C for
// membrane potentials, the gates' total rate (alpha + beta, eps cosh(...), r_q, the muscle
// activation's rate) for gates, 0 for the mechanics. The split f_I = -kappa(y) * (y - c),
// f_E = f - f_I is exact for any kappa and constant c; kappa only decides how much of each
// equation the implicit part carries (the presynaptic gates and modulations, small and slow,
// stay explicit). c = stiff_offsets(): each potential's leak reversal E_L, 0 for gates, so
// that the implicit part's dependence on other states (kappa'(y) (y - c): a presynaptic
// potential through the synapse's conductance) stays as small as the potential's distance
// from rest, not from 0 mV. The diagonal of f_I's Jacobian is -kappa up to the dependence of kappa on
// the state itself (the NaP current's m_inf(V)), which the Newton iteration absorbs.
#include <cstddef>
#include <vector>

#include "model/network_model.hpp"

namespace phasmid::model {

struct StiffRateOptions {
  bool gates = true;  // also the gates (false: membrane potentials only)
};

// kappa (model.num_states() entries, 1/ms) at state y and parameters p.
void stiff_rates(const NetworkModel& model, const double* y, const double* p, double* kappa,
                 const StiffRateOptions& options = {});
// c (model.num_states() entries): E_L (mV) at every membrane potential, 0 elsewhere.
std::vector<double> stiff_offsets(const NetworkModel& model, const double* p);

}  // namespace phasmid::model
