// Fuzz target: the config loader (TOML -> scenario) as the verbs use it: parse, build the
// scenario ([model], [parameters], [[triggers]]), [simulation], the [sweep] design and its
// scenario factory, the [fit] problem and, for ODE kinds, [sensitivity]. Nothing is run.
// Each step is tried on its own, so a config broken for one verb still reaches the others.
#include "config/config.hpp"
#include "config/fit_section.hpp"
#include "config/sensitivity_section.hpp"
#include "config/sweep_inputs.hpp"
#include "fit/fit_spec.hpp"
#include "fit/residual_problem.hpp"
#include "fuzz_input.hpp"
#include "model/ode_model.hpp"
#include "scenario/scenario.hpp"
#include "sweep/sweep_runner.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace phasmid;
  config::Config cfg;
  try {
    cfg = config::parse_config(fuzz::as_text(data, size), "fuzz.toml");
  } catch (const Error&) {
    return 0;
  }
  std::unique_ptr<scenario::Scenario> sc;
  fuzz::attempt([&] { sc = config::build_scenario(cfg); });
  if (!sc) return 0;
  fuzz::attempt([&] {
    const config::SimulationSettings s = config::simulation_settings(cfg, sc.get());
    if (const model::OdeModel* m = sc->ode_model()) config::sensitivity_job(cfg, *m, s);
  });
  fuzz::attempt([&] { config::sweep_inputs(cfg, {}); });
  fuzz::attempt([&] {
    sc->make_fit(config::fit_spec(cfg, *sc, fit::FitOverrides{}));
  });
  return 0;
}
