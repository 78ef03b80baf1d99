#include "sensitivity/floquet.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "io/h5_file.hpp"

namespace phasmid::sensitivity {

InitialValueModel::InitialValueModel(const model::OdeModel& base, std::vector<double> y0, double t0)
    : base_(base), y0_(std::move(y0)), t0_(t0), nb_(base.parameters().size()) {
  if (y0_.size() != base.num_states()) throw Error("internal: initial state size mismatch");
  for (const auto& par : base.parameters().all()) params_.add(par);
  for (const auto& s : base.states()) add_state(s.name, s.unit);
  for (const auto& s : base.states())
    params_.add({"delta." + s.name, 0.0, s.unit, "phasmid", "shift of the initial state (for dy/dy0)"});
  angles_ = base.angles();
}

std::vector<double> InitialValueModel::initial_state(const std::vector<double>&) const { return y0_; }

std::vector<double> InitialValueModel::breakpoints(const std::vector<double>& p, double t_end) const {
  std::vector<double> pb(p.begin(), p.begin() + nb_), out;
  for (double b : base_.breakpoints(pb, t0_ + t_end))
    if (b > t0_) out.push_back(b - t0_);
  return out;
}

std::vector<double> InitialValueModel::extend(const std::vector<double>& p_base) const {
  std::vector<double> p = p_base;
  p.resize(nb_ + num_states(), 0.0);
  return p;
}

solver::RootSpec default_section(const model::OdeModel& model) {
  if (model.angles().empty()) throw Error("model has no joint angle: give the Poincare section explicitly");
  return {model.angles()[0].velocity_state, 0.0, -1};
}

PeriodicOrbit find_periodic_orbit(const model::OdeModel& model, const std::vector<double>& p,
                                  const FloquetOptions& opt) {
  solver::Simulator sim(model, opt.solver);
  const double t_end = opt.transient_ms + 2.0 * opt.max_period_ms;
  solver::SolveResult r = sim.run(p, {0.0, t_end}, {opt.section});
  std::vector<const solver::Event*> hits;
  for (const auto& e : r.events)
    if (opt.section.direction == 0 || e.direction == opt.section.direction) hits.push_back(&e);
  if (hits.size() < 2 || hits[hits.size() - 2]->t < opt.transient_ms)
    throw Error("no periodic orbit found: fewer than two section crossings after the transient");
  const solver::Event& a = *hits[hits.size() - 2];
  const solver::Event& b = *hits.back();
  return {a.t, b.t - a.t, a.y};
}

Eigen::MatrixXd monodromy_matrix(const model::OdeModel& model, const std::vector<double>& p, const PeriodicOrbit& orbit,
                                 const solver::SolverOptions& solver_options, std::vector<double>* y_end,
                                 solver::SolverStats* stats) {
  InitialValueModel iv(model, orbit.y0, orbit.t0);
  const size_t n = model.num_states(), nb = iv.num_base_parameters();
  std::vector<size_t> sens;
  for (size_t i = 0; i < n; ++i) sens.push_back(nb + i);
  solver::Simulator sim(iv, solver_options);
  solver::SolveResult r = sim.run(iv.extend(p), {0.0, orbit.period_ms}, {}, sens);
  Eigen::MatrixXd phi(n, n);
  const size_t k = r.t.size() - 1;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j) phi(i, j) = r.sens(k, i, j) + (i == j ? 1.0 : 0.0);
  if (y_end) y_end->assign(r.y.begin() + k * n, r.y.begin() + (k + 1) * n);
  if (stats) *stats = r.stats;
  return phi;
}

FloquetResult floquet_analysis(const model::OdeModel& model, const std::vector<double>& p,
                               const FloquetOptions& opt) {
  FloquetResult res;
  res.orbit = find_periodic_orbit(model, p, opt);
  std::vector<double> y_end;
  res.monodromy = monodromy_matrix(model, p, res.orbit, opt.solver, &y_end, &res.monodromy_stats);
  res.seconds = res.monodromy_stats.wall_seconds;
  Eigen::EigenSolver<Eigen::MatrixXd> es(res.monodromy, false);
  for (Eigen::Index i = 0; i < es.eigenvalues().size(); ++i) res.multipliers.push_back(es.eigenvalues()[i]);
  std::sort(res.multipliers.begin(), res.multipliers.end(),
            [](const std::complex<double>& a, const std::complex<double>& b) { return std::abs(a) > std::abs(b); });
  res.trivial_multiplier_error = INFINITY;
  for (auto& m : res.multipliers) res.trivial_multiplier_error = std::min(res.trivial_multiplier_error, std::abs(m - 1.0));
  // Closure: the state one period later (from the monodromy run) against the start.
  const size_t n = model.num_states();
  for (size_t i = 0; i < n; ++i) res.closure_error = std::max(res.closure_error, std::abs(y_end[i] - res.orbit.y0[i]));
  Eigen::VectorXd f0(n), f1(n);
  model.rhs(res.orbit.t0, res.orbit.y0.data(), p.data(), f0.data());
  model.rhs(res.orbit.t0 + res.orbit.period_ms, y_end.data(), p.data(), f1.data());
  res.flow_identity_error = (res.monodromy * f0 - f1).norm() / f1.norm();
  return res;
}

PhaseResponseCurve phase_response_curve(const model::OdeModel& model, const std::vector<double>& p,
                                        const PrcOptions& opt) {
  if (opt.state >= model.num_states()) throw Error("PRC: state index out of range");
  if (opt.n_phases == 0 || opt.cycles_after < 1) throw Error("PRC: need n_phases >= 1 and cycles_after >= 1");
  PhaseResponseCurve prc;
  prc.orbit = find_periodic_orbit(model, p, opt.floquet);
  const double T = prc.orbit.period_ms, t0 = prc.orbit.t0;
  InitialValueModel iv(model, prc.orbit.y0, t0);
  std::vector<double> grid;
  for (size_t k = 0; k < opt.n_phases; ++k) grid.push_back(T * k / opt.n_phases);
  solver::SolveResult along = solver::Simulator(iv, opt.floquet.solver).run(iv.extend(p), grid);
  const size_t n = model.num_states();
  for (size_t k = 0; k < opt.n_phases; ++k) {
    const double phi = static_cast<double>(k) / opt.n_phases;
    std::vector<double> y(n);
    for (size_t i = 0; i < n; ++i) y[i] = along.state(k, i);
    y[opt.state] += opt.amplitude;
    const double t_kick = t0 + phi * T;
    InitialValueModel kicked(model, y, t_kick);
    const double span = (opt.cycles_after + 0.5) * T;
    solver::SolveResult r = solver::Simulator(kicked, opt.floquet.solver).run(kicked.extend(p), {0.0, span}, {opt.floquet.section});
    const solver::Event* last = nullptr;
    for (const auto& e : r.events)
      if (opt.floquet.section.direction == 0 || e.direction == opt.floquet.section.direction) last = &e;
    if (!last) throw Error("PRC: the perturbed run never crossed the section");
    const double since = t_kick + last->t - t0;  // time since the reference crossing
    const double cycles = std::round(since / T);
    prc.phase.push_back(phi);
    prc.shift.push_back((cycles * T - since) / T);
  }
  return prc;
}

void write_floquet_h5(io::H5Writer& out, const model::OdeModel& model, const FloquetResult& res) {
  const size_t n = model.num_states();
  const std::string g = "/sensitivity/floquet";
  out.ensure_group(g);
  out.write_scalar(g + "/period_ms", res.orbit.period_ms, "ms");
  out.write_scalar(g + "/t0", res.orbit.t0, "ms");
  out.write_scalar(g + "/closure_error", res.closure_error, "state units");
  out.write_scalar(g + "/trivial_multiplier_error", res.trivial_multiplier_error, "1");
  out.write_scalar(g + "/flow_identity_error", res.flow_identity_error, "1");
  std::vector<double> phi(n * n), re, im, ab;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j) phi[i * n + j] = res.monodromy(i, j);
  out.write(g + "/monodromy", phi, "state unit i per state unit j (row i, column j)", {n, n});
  for (auto& m : res.multipliers) {
    re.push_back(m.real());
    im.push_back(m.imag());
    ab.push_back(std::abs(m));
  }
  out.write(g + "/multipliers_real", re, "1");
  out.write(g + "/multipliers_imag", im, "1");
  out.write(g + "/multipliers_abs", ab, "1");
  std::vector<std::string> names;
  for (auto& s : model.states()) names.push_back(s.name);
  out.write(g + "/state_names", names);
  out.write(g + "/state_on_section", res.orbit.y0, "state units (see state_names)");
}

void write_prc_h5(io::H5Writer& out, const model::OdeModel& model, const PrcOptions& opt,
                  const PhaseResponseCurve& prc) {
  const std::string g = "/sensitivity/prc";
  out.ensure_group(g);
  out.write(g + "/phase", prc.phase, "cycles");
  out.write(g + "/shift", prc.shift, "cycles (positive = advance)");
  out.set_attribute(g, "state", model.states().at(opt.state).name);
  out.set_attribute(g, "amplitude", opt.amplitude);
  out.set_attribute(g + "/shift", "amplitude_unit", model.states().at(opt.state).unit);
  out.write_scalar(g + "/period_ms", prc.orbit.period_ms, "ms");
}

}  // namespace phasmid::sensitivity
