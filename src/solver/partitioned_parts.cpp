#include "solver/partitioned_parts.hpp"

#include <sunmatrix/sunmatrix_dense.h>

#include <cstdint>
#include <cstring>

#include "common/error.hpp"
#include "solver/dopri_session.hpp"
#include "solver/partitioned_simulator.hpp"
#include "solver/simulator.hpp"

namespace phasmid::solver {
namespace partitioned {

using model::kJacobianChunk;

double PartSolver::export_value(size_t e, double at) const {
  return horner(coef, exports.size(), e, order, at - t_poly);
}

namespace {

// Whether every x[i] is finite: its exponent bits are not all ones. Integer tests are exact in
// any order, so the loop vectorises and has no chain of dependent additions (a sum of x - x,
// the previous form, cost one floating-point add latency per entry).
bool all_finite(const double* x, size_t n) {
  constexpr uint64_t kExponent = 0x7ff0000000000000ull;
  uint64_t bad = 0;
  for (size_t i = 0; i < n; ++i) {
    uint64_t bits;
    std::memcpy(&bits, x + i, sizeof bits);
    bad |= static_cast<uint64_t>((bits & kExponent) == kExponent);
  }
  return bad == 0;
}

// Input i of the part at time t from its owner's polynomial (windowed runs: from the snapshot
// of the part's present window).
double input_value(const PartSolver& ps, size_t i, double t) {
  const auto& [owner, e] = ps.input_from[i];
  const PartSolver& o = *ps.run->parts[owner];
  return ps.run->windowed ? ps.in_snap[owner].value(o.exports.size(), e, t) : o.export_value(e, t);
}

// The part's inputs at time t, written into a full-size vector at their indices.
template <class Scalar>
void fill_inputs(const PartSolver& ps, double t, std::vector<Scalar>& full) {
  for (size_t i = 0; i < ps.inputs.size(); ++i) full[ps.inputs[i]] = Scalar(input_value(ps, i, t));
}

// The part's inputs at time t, packed (u[i] = input i). Sequential runs read each owner's
// polynomial here, inlined, so that the inputs' Horner chains overlap rather than wait on one
// another through a call per input.
void gather_inputs(const PartSolver& ps, double t, double* u) {
  const size_t m = ps.input_from.size();
  if (ps.run->windowed) {
    for (size_t i = 0; i < m; ++i) u[i] = input_value(ps, i, t);
    return;
  }
  for (size_t i = 0; i < m; ++i) {
    const auto& [owner, e] = ps.input_from[i];
    u[i] = ps.run->parts[owner]->export_value(e, t);
  }
}

int part_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* ud) {
  auto* ps = static_cast<PartSolver*>(ud);
  const double* yv = N_VGetArrayPointer(y);
  double* out = N_VGetArrayPointer(ydot);
  const size_t n = ps->states.size();
  if (ps->eq->packed()) {  // a compiled part reads its states and inputs where they are
    gather_inputs(*ps, t, ps->u.data());
    ps->eq->rhs_packed(t, yv, ps->u.data(), ps->run->p->data(), out);
  } else {
    fill_inputs(*ps, t, ps->yfull);
    for (size_t i = 0; i < n; ++i) ps->yfull[ps->states[i]] = yv[i];
    ps->eq->rhs(t, ps->yfull.data(), ps->run->p->data(), ps->ffull.data());
    for (size_t i = 0; i < n; ++i) out[i] = ps->ffull[ps->states[i]];
  }
  return all_finite(out, n) ? 0 : 1;  // recoverable: the integrator retries a smaller step
}

// Dense Jacobian of the part's own equations by forward-mode AD (inputs held fixed).
int part_jac(sunrealtype t, N_Vector y, N_Vector, SUNMatrix Jm, void* ud, N_Vector, N_Vector, N_Vector) {
  auto* ps = static_cast<PartSolver*>(ud);
  fill_inputs(*ps, t, ps->yK);
  const double* yv = N_VGetArrayPointer(y);
  const size_t n = ps->states.size();
  double* J = SUNDenseMatrix_Data(Jm);
  for (size_t c0 = 0; c0 < n; c0 += kJacobianChunk) {
    for (size_t i = 0; i < n; ++i) {
      JetK& v = ps->yK[ps->states[i]];
      v = JetK(yv[i]);
      if (i >= c0 && i < c0 + kJacobianChunk) v.v[i - c0] = 1.0;
    }
    ps->eq->rhs(t, ps->yK.data(), ps->run->pK.data(), ps->fK.data());
    for (size_t k = 0; k < kJacobianChunk && c0 + k < n; ++k)
      for (size_t i = 0; i < n; ++i) J[(c0 + k) * n + i] = ps->fK[ps->states[i]].v[k];
  }
  return 0;
}

int part_roots(sunrealtype, N_Vector y, sunrealtype* g, void* ud) {
  auto* ps = static_cast<PartSolver*>(ud);
  for (size_t r = 0; r < ps->roots.size(); ++r)
    g[r] = NV_Ith_S(y, ps->root_state[r]) - (*ps->run->roots)[ps->roots[r]].level;
  return 0;
}

// A part's integrator settings: a stiff part (ModelPartition::stiff) of an explicit run is
// CVODES BDF at stiff_part_tol, where an explicit method's steps would be bounded by stability.
SolverOptions options_of_part(const SolverOptions& options, bool stiff) {
  if (!stiff || !is_explicit_rk(options.integrator)) return options;
  SolverOptions o = options;
  o.integrator = IntegratorKind::Bdf;
  o.rtol = o.atol = options.stiff_part_tol;
  o.atol_by_unit = options.stiff_part_atol_by_unit;
  return o;
}

}  // namespace

void build_parts(Run& run, RunParameters& params, const model::OdeModel& model, const model::ModelPartition& P,
                 const std::vector<RootSpec>& roots, const SolverOptions& options) {
  const size_t n = model.num_states();
  std::vector<size_t> part_of(n), local_of(n);
  for (size_t k = 0; k < P.size(); ++k)
    for (size_t i = 0; i < P.states[k].size(); ++i) {
      part_of[P.states[k][i]] = k;
      local_of[P.states[k][i]] = i;
    }
  for (size_t k = 0; k < P.size(); ++k) {
    auto ps = std::make_unique<PartSolver>();
    ps->run = &run;
    ps->name = P.names[k];
    ps->states = P.states[k];
    ps->history = StepHistory(ps->states.size());
    ps->inputs = P.inputs[k];
    ps->stiff = P.is_stiff(k);
    ps->eq = model.make_part(P, k);
    if (!ps->eq) throw Error("internal: model " + model.kind() + " has no equations for part " + ps->name);
    params.bind(ps->eq.get());
    compile_if_asked(ps->eq.get(), options);
    ps->yfull.assign(n, 0.0);
    ps->ffull.assign(n, 0.0);
    ps->u.assign(ps->inputs.size(), 0.0);
    ps->yK.assign(n, JetK(0.0));
    ps->fK.assign(n, JetK(0.0));
    run.parts.push_back(std::move(ps));
  }
  for (auto& ps : run.parts)
    for (size_t g : ps->inputs) {
      PartSolver& owner = *run.parts[part_of[g]];
      const size_t local = local_of[g];
      auto at = std::find(owner.exports.begin(), owner.exports.end(), local);
      if (at == owner.exports.end()) at = owner.exports.insert(owner.exports.end(), local);
      ps->input_from.emplace_back(part_of[g], static_cast<size_t>(at - owner.exports.begin()));
    }
  for (auto& ps : run.parts) {
    for (const auto& from : ps->input_from) ps->owners.push_back(from.first);
    std::sort(ps->owners.begin(), ps->owners.end());
    ps->owners.erase(std::unique(ps->owners.begin(), ps->owners.end()), ps->owners.end());
    ps->in_snap.resize(run.parts.size());
  }
  for (size_t r = 0; r < roots.size(); ++r) {
    PartSolver& ps = *run.parts[part_of.at(roots[r].state)];
    ps.roots.push_back(r);
    ps.root_state.push_back(local_of[roots[r].state]);
  }
}

void start_sessions(Run& run, const model::OdeModel& model, const std::vector<std::unique_ptr<SundialsContext>>& contexts,
                    const SolverOptions& options, const std::vector<double>& y0, double first_stop) {
  for (size_t k = 0; k < run.parts.size(); ++k) {
    PartSolver& ps = *run.parts[k];
    SUNContext ctx = contexts[std::min(k, contexts.size() - 1)]->get();
    std::vector<double> own(ps.states.size());
    for (size_t i = 0; i < ps.states.size(); ++i) own[i] = y0[ps.states[i]];
    // Before its first step a part's polynomial is its initial value.
    ps.coef.assign(static_cast<size_t>(kMaxOrder + 1) * ps.exports.size(), 0.0);
    for (size_t e = 0; e < ps.exports.size(); ++e) ps.coef[e] = y0[ps.states[ps.exports[e]]];
    const SolverOptions part_options = options_of_part(options, ps.stiff);
    if (is_explicit_rk(part_options.integrator)) {
      ps.session = std::make_unique<DopriSession>(ctx, part_options, own.data(), own.size(), part_rhs, &ps);
    } else {
      auto cv = std::make_unique<CvodesSession>(ctx, part_options, own.data(), own.size(), part_rhs, &ps);
      // Parts are small (a joint: 20-26 states): dense LU with the compiled kernels.
      cv->set_linear_solver(LinearSystem::Dense, 0, 0, part_jac);
      ps.session = std::move(cv);
    }
    if (!part_options.atol_by_unit.empty()) ps.session->set_state_atol(state_atol(model, part_options, ps.states));
    std::vector<int> dirs;
    for (size_t r : ps.roots) dirs.push_back((*run.roots)[r].direction);
    ps.session->init_roots(dirs, part_roots);
    ps.session->set_stop_time(first_stop);
  }
}

}  // namespace partitioned

void check_atol_units(const model::OdeModel& model, const SolverOptions& options) {
  std::vector<std::string> units;  // in the order of their first state
  for (const model::StateInfo& s : model.states())
    if (std::find(units.begin(), units.end(), s.unit) == units.end()) units.push_back(s.unit);
  auto check = [&](const char* key, const std::vector<std::pair<std::string, double>>& by_unit) {
    for (const auto& entry : by_unit) {
      if (std::find(units.begin(), units.end(), entry.first) != units.end()) continue;
      std::string list;
      for (const std::string& u : units) list += (list.empty() ? "'" : ", '") + u + "'";
      throw Error(std::string("solver option '") + key + "': no state of this model has unit '" + entry.first +
                  "' (its units: " + list + ")");
    }
  };
  check("atol_by_unit", options.atol_by_unit);
  check("stiff_part_atol_by_unit", options.stiff_part_atol_by_unit);
}

// The absolute tolerance of each of `states` (SolverOptions::atol_by_unit).
std::vector<double> state_atol(const model::OdeModel& model, const SolverOptions& options,
                               const std::vector<size_t>& states) {
  std::vector<double> atol(states.size(), options.atol);
  for (size_t i = 0; i < states.size(); ++i)
    for (const auto& [unit, value] : options.atol_by_unit)
      if (model.states()[states[i]].unit == unit) atol[i] = value;
  return atol;
}

}  // namespace phasmid::solver
