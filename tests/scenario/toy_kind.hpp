#pragma once
// A model kind that lives only in the test tree, registered the way a user's kind would be
// (scenario/registry.hpp): the van der Pol oscillator of scenario/kinds/van_der_pol.hpp under
// the name "toy_vdp" with names toy.* (toy.mu, toy.fti.gamma), its x presented as a joint angle
// so that the generic features (period, extremal angles) apply. Its known periods (van der Pol
// 1926; e.g. Strogatz, Nonlinear Dynamics and Chaos, 2nd ed., Sect. 7.5; T(1) = 6.6633,
// T(2) = 7.6299, T(5) = 11.6122) check the whole chain config -> kind -> scenario -> verb.
#include <memory>

#include "scenario/kinds/van_der_pol.hpp"
#include "scenario/ode_scenario.hpp"
#include "scenario/registry.hpp"

namespace phasmid::test {

// The kind's one registration line (a built-in kind's would be in builtin_kinds.def).
inline const scenario::RegisterModelKind kToyKind{
    {"toy_vdp", "van der Pol oscillator (test kind)", {}, [](const scenario::ModelSection&) {
       return std::unique_ptr<scenario::Scenario>(std::make_unique<scenario::OdeScenario>(
           std::make_unique<scenario::kinds::VanDerPolModel>("toy", "toy_vdp")));
     }}};

}  // namespace phasmid::test
