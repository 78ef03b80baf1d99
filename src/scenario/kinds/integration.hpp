#pragma once
// How each model kind integrates (docs/solver.md "How each kind integrates"): a kind's policy
// turns what the user asked ([simulation], [simulation.expert], the Python keywords: an
// IntegrationRequest) into a fully resolved solver::SolverOptions — which parts, which method
// per part, tolerances per part, whether to compile the right-hand side. Nothing else in
// phasmid chooses these: the simulator runs what it is given.
//
// Contract of every policy:
//  - with an empty request it returns the kind's default: the fastest setting measured whose
//    features stay within 0.01 ms and 0.01 deg of CVODES BDF at rtol = atol = 1e-10 as one
//    system (tests/scenario/configs_accuracy.test.sh checks every shipped config);
//  - a given rtol/atol is mapped onto the kind's parts as docs/solver.md states; a given expert
//    key replaces the kind's choice for that key only;
//  - a request that combines settings which would change nothing or cannot run together is an
//    Error naming the option (the config layer adds file:line).
#include <functional>

#include "scenario/scenario.hpp"

namespace phasmid::model {
enum class MotoneuronModel;  // model/network_model.hpp
}

namespace phasmid::scenario::kinds {

using Integration = std::function<solver::SolverOptions(const IntegrationRequest&)>;

// One system on CVODES BDF at rtol = atol = `tol` (the given ones if set); `integrator =
// "dopri5"` runs Dormand-Prince on it at the same tolerances. The mechanical models and the
// test kinds: small, smooth systems for which BDF's long steps win.
Integration whole_system_bdf(double tol = 1e-8);

// The CPG-interneuron-motoneuron networks (single_joint, leg, three_legs, curve_walking).
// Spiking motoneurons: each joint network's spiking cells apart from its stiff network
// (Partitioning::Neurons), Dormand-Prince on the spiking parts at rtol = atol = `spiking_tol`,
// the network parts on CVODES BDF at rtol = atol = spiking_tol * kNetworkPartRatio with
// potentials at atol = spiking_tol * kNetworkMvRatio mV, compiled right-hand sides. A user's
// rtol and atol take spiking_tol's place in these products: every part tighter or looser by
// the same factor. Rate motoneurons: CVODES BDF per joint network at rtol = atol = `rate_tol`.
Integration network_integration(model::MotoneuronModel mn, double rate_tol, double spiking_tol);

// The ratios of the network parts' tolerances to the spiking parts' (1e-7 and 1e-4 mV at 3e-5):
// the BDF parts, whose potentials pace the spiking cells, need far tighter tolerances than the
// explicit parts, but not their potentials at the 1e-7 mV that rtol alone would give.
inline constexpr double kNetworkPartRatio = 1e-7 / 3e-5;
inline constexpr double kNetworkMvRatio = 1e-4 / 3e-5;

}  // namespace phasmid::scenario::kinds
