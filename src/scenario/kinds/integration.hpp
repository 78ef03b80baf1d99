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

// The tolerances of a spiking network's default (docs/solver.md "How each kind integrates"):
// rtol = atol of the explicit (spiking) parts; rtol = atol of the CVODES BDF network parts;
// their potentials' atol (mV). A user's rtol scales the network parts' tolerance by
// rtol / spiking_tol, a user's atol their potentials' atol by atol / spiking_tol: every part
// tighter (or looser) by the same factor.
struct SpikingTolerances {
  double spiking_tol = 3e-5;
  double network_tol = 1e-7;
  double network_mv = 1e-4;
};

// The CPG-interneuron-motoneuron networks (single_joint, leg, three_legs, curve_walking).
// Spiking motoneurons: each joint network's spiking cells apart from its stiff network
// (Partitioning::Neurons), Dormand-Prince on the spiking parts, the network parts on CVODES
// BDF, at `spiking`; compiled right-hand sides. Rate motoneurons: CVODES BDF per joint network
// at rtol = atol = `rate_tol`.
Integration network_integration(model::MotoneuronModel mn, double rate_tol, SpikingTolerances spiking = {});

}  // namespace phasmid::scenario::kinds
