// Model kind "van_der_pol" (scenario/kinds/van_der_pol.hpp): a test kind for continuation in mu
// (docs/continuation.md); its periods are tabulated in the literature
// (tests/continuation/test_continuation.cpp).
#include "scenario/kinds/van_der_pol.hpp"

#include "scenario/ode_scenario.hpp"
#include "scenario/registry.hpp"

namespace phasmid::scenario {

ModelKind van_der_pol_kind() {
  return {"van_der_pol", "van der Pol oscillator x'' - mu (1 - x^2) x' + x = 0, time in ms (test kind)", {},
          [](const ModelSection&) -> std::unique_ptr<Scenario> {
            return std::make_unique<OdeScenario>(std::make_unique<kinds::VanDerPolModel>("vdp", "van_der_pol"));
          }};
}

}  // namespace phasmid::scenario
