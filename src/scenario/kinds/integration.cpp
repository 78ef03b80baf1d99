#include "scenario/kinds/integration.hpp"

#include <algorithm>

#include "common/error.hpp"
#include "model/network_model.hpp"

namespace phasmid::scenario::kinds {
namespace {

using solver::IntegratorKind;
using solver::Partitioning;

// The expert keys every kind takes as given (they choose how the chosen method runs, not
// which: threads and windows of partitioned runs, the Newton linear system, the step limit,
// absolute tolerances by unit).
void apply_common(const IntegrationRequest& r, solver::SolverOptions& o) {
  if (r.max_step_ms) o.max_step_ms = *r.max_step_ms;
  if (r.threads) o.threads = *r.threads;
  if (r.window_ms) o.window_ms = *r.window_ms;
  if (r.linear_solver) o.linear_solver = *r.linear_solver;
  if (r.atol_by_unit) o.atol_by_unit = *r.atol_by_unit;
  if (r.compiled_rhs) o.compiled_rhs = *r.compiled_rhs;
}

// The checks that concern combinations (each key's own range is the config layer's).
void check_combination(const IntegrationRequest& r, const solver::SolverOptions& o) {
  const bool network_parts = o.partitioning == Partitioning::Neurons && solver::is_explicit_rk(o.integrator);
  if (r.network_tol && !network_parts)
    throw Error("expert.network_tol applies only with partitioning = \"neurons\" and integrator = \"dopri5\", "
                "where the network parts run CVODES BDF (docs/solver.md)");
  if (r.network_atol_by_unit && !network_parts)
    throw Error("expert.network_atol_by_unit applies only with partitioning = \"neurons\" and integrator = "
                "\"dopri5\", where the network parts run CVODES BDF (docs/solver.md)");
  if (o.partitioning == Partitioning::Neurons && o.threads >= 2)
    throw Error(std::string("expert.partitioning = \"neurons\" runs on one thread (expert.threads = 1): ") +
                solver::kNeuronsOnOneThread);
}

solver::SolverOptions spiking_network(const IntegrationRequest& r, double spiking_tol) {
  solver::SolverOptions o;
  apply_common(r, o);
  o.integrator = r.integrator.value_or(IntegratorKind::Dopri5);
  if (o.integrator == IntegratorKind::Bdf) {
    // BDF on the whole network: the spikes need 1e-8 to keep the features within the gate.
    o.partitioning = r.partitioning.value_or(Partitioning::Off);
    o.rtol = r.rtol.value_or(1e-8);
    o.atol = r.atol.value_or(1e-8);
  } else {
    // The spiking cells apart (one thread only); with threads one Dormand-Prince per joint
    // network, which the spiking cells' coupling would otherwise cost accuracy at 1e-6.
    o.partitioning = r.partitioning.value_or(o.threads >= 2 ? Partitioning::On : Partitioning::Neurons);
    const double tol = o.partitioning == Partitioning::Neurons ? spiking_tol : 1e-6;
    o.rtol = r.rtol.value_or(tol);
    o.atol = r.atol.value_or(tol);
    if (o.partitioning == Partitioning::Neurons) {
      // A given tolerance tightens the spiking cells apart, never loosens them below the
      // accuracy gate: configs give rtol for the whole-system BDF runs of their analyses
      // (sensitivities, fits), where 1e-6 means far more than on these parts.
      o.rtol = std::min(o.rtol, spiking_tol);
      o.atol = std::min(o.atol, spiking_tol);
    }
    if (o.partitioning == Partitioning::Neurons) {
      o.stiff_part_tol = r.network_tol.value_or(o.rtol * kNetworkPartRatio);
      o.stiff_part_atol_by_unit = r.network_atol_by_unit.value_or(
          std::vector<std::pair<std::string, double>>{{"mV", o.atol * kNetworkMvRatio}});
    }
  }
  o.compiled_rhs = r.compiled_rhs.value_or(true);
  check_combination(r, o);
  return o;
}

// Rate motoneurons: the interneurons' potentials are too stiff for an explicit method, and
// without spikes every joint network keeps its features on its own step size.
solver::SolverOptions rate_network(const IntegrationRequest& r, double rate_tol) {
  solver::SolverOptions o;
  apply_common(r, o);
  o.integrator = r.integrator.value_or(IntegratorKind::Bdf);
  o.partitioning = r.partitioning.value_or(Partitioning::On);
  const double tol = o.integrator == IntegratorKind::Bdf ? rate_tol : 1e-6;
  o.rtol = r.rtol.value_or(tol);
  o.atol = r.atol.value_or(tol);
  if (r.network_tol) o.stiff_part_tol = *r.network_tol;
  if (r.network_atol_by_unit) o.stiff_part_atol_by_unit = *r.network_atol_by_unit;
  o.compiled_rhs = r.compiled_rhs.value_or(false);
  check_combination(r, o);
  return o;
}

}  // namespace

Integration whole_system_bdf(double tol) {
  return [tol](const IntegrationRequest& r) {
    solver::SolverOptions o;
    apply_common(r, o);
    o.integrator = r.integrator.value_or(IntegratorKind::Bdf);
    o.partitioning = r.partitioning.value_or(Partitioning::Off);
    o.rtol = r.rtol.value_or(tol);
    o.atol = r.atol.value_or(tol);
    if (r.network_tol) o.stiff_part_tol = *r.network_tol;
    if (r.network_atol_by_unit) o.stiff_part_atol_by_unit = *r.network_atol_by_unit;
    check_combination(r, o);
    return o;
  };
}

Integration network_integration(model::MotoneuronModel mn, double rate_tol, double spiking_tol) {
  if (mn == model::MotoneuronModel::Spiking)
    return [spiking_tol](const IntegrationRequest& r) { return spiking_network(r, spiking_tol); };
  return [rate_tol](const IntegrationRequest& r) { return rate_network(r, rate_tol); };
}

}  // namespace phasmid::scenario::kinds
