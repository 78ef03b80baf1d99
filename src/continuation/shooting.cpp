#include "continuation/shooting.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace phasmid::continuation {

CycleModel::CycleModel(const model::OdeModel& base, std::vector<double> y0, double t0)
    : sensitivity::InitialValueModel(base, std::move(y0), t0) {
  structure_ = base.structure();
  if (t0 == 0.0) set_triggers(base.triggers());
}

Shot shoot(const model::OdeModel& model, std::vector<double> p, const ParameterPath& path, const Cycle& cycle,
           const solver::SolverOptions& solver) {
  path.apply(p, cycle.parameter);
  CycleModel cm(model, cycle.y0, cycle.t0);
  const size_t n = model.num_states(), nb = cm.num_base_parameters();
  std::vector<size_t> sens;
  for (size_t i = 0; i < n; ++i) sens.push_back(nb + i);
  sens.insert(sens.end(), path.index.begin(), path.index.end());
  solver::SolverOptions so = solver;
  so.progress = false;
  so.sensitivities_at_outputs = true;
  std::vector<double> pe = cm.extend(p);
  const solver::SolveResult r = solver::Simulator(cm, so).run(pe, {0.0, cycle.period_ms}, {}, sens);
  const size_t k = r.t.size() - 1;
  Shot s;
  s.residual.resize(n);
  s.monodromy.resize(n, n);
  Eigen::VectorXd y_end(n);
  for (size_t i = 0; i < n; ++i) {
    y_end[i] = r.state(k, i);
    s.residual[i] = y_end[i] - cycle.y0[i];
    for (size_t j = 0; j < n; ++j) s.monodromy(i, j) = r.sens(k, i, j) + (i == j ? 1.0 : 0.0);
  }
  if (!path.index.empty()) s.dy_dparam = Eigen::VectorXd::Zero(n);
  for (size_t j = 0; j < path.index.size(); ++j)
    for (size_t i = 0; i < n; ++i) s.dy_dparam[i] += path.slope[j] * r.sens(k, i, n + j);
  // f at the end of the cycle, in the mode the run ended in (the commands it resolved).
  for (const auto& c : r.commands) pe[c.parameter] = c.t_ms;
  s.f_end.resize(n);
  cm.rhs(cycle.period_ms, y_end.data(), pe.data(), s.f_end.data());  // InitialValueModel adds t0
  return s;
}

Cycle newton_fixed_parameter(const model::OdeModel& model, const std::vector<double>& p, const Cycle& guess,
                             const ShootingOptions& o, NewtonReport& report, Shot* shot_out) {
  const size_t n = model.num_states(), sec = o.section.state;
  Cycle c = guess;
  report = {};
  for (int it = 0;; ++it) {
    Shot s = shoot(model, p, {}, c, o.solver);
    report.iterations = it;
    report.residual = s.max_residual();
    const double tol = o.tolerance * growth(s.monodromy);
    if (report.residual < tol && std::abs(c.y0[sec] - o.section.level) < o.tolerance) {
      report.converged = true;
      if (shot_out) *shot_out = std::move(s);
      return c;
    }
    if (it >= o.max_iterations) return c;
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n + 1, n + 1);
    J.topLeftCorner(n, n) = s.monodromy - Eigen::MatrixXd::Identity(n, n);
    J.topRightCorner(n, 1) = s.f_end;
    J(n, sec) = 1.0;
    Eigen::VectorXd rhs(n + 1);
    rhs.head(n) = -s.residual;
    rhs[n] = -(c.y0[sec] - o.section.level);
    const Eigen::VectorXd d = J.colPivHouseholderQr().solve(rhs);
    for (size_t i = 0; i < n; ++i) c.y0[i] += d[i];
    c.period_ms += d[n];
    if (!(c.period_ms > 0.0)) return c;
  }
}

Cycle find_cycle(const model::OdeModel& model, const std::vector<double>& p, const ShootingOptions& o,
                 NewtonReport& report, Shot* shot) {
  sensitivity::FloquetOptions fo;
  fo.section = o.section;
  fo.transient_ms = o.transient_ms;
  fo.max_period_ms = o.max_period_ms;
  fo.solver = o.solver;
  fo.solver.progress = false;
  const sensitivity::PeriodicOrbit orbit = sensitivity::find_periodic_orbit(model, p, fo);
  const double t0 = model.triggers().empty() ? orbit.t0 : 0.0;
  Cycle c = newton_fixed_parameter(model, p, {orbit.y0, orbit.period_ms, 0.0, t0}, o, report, shot);
  if (!report.converged)
    throw Error("Newton shooting did not converge from the cycle after the transient (residual " +
                std::to_string(report.residual) + " after " + std::to_string(report.iterations) + " iterations)");
  return c;
}

double growth(const Eigen::MatrixXd& monodromy) {
  const auto mu = multipliers(monodromy);
  return std::max(1.0, mu.empty() ? 0.0 : std::abs(mu.front()));
}

std::vector<std::complex<double>> multipliers(const Eigen::MatrixXd& monodromy) {
  Eigen::EigenSolver<Eigen::MatrixXd> es(monodromy, false);
  std::vector<std::complex<double>> mu;
  for (Eigen::Index i = 0; i < es.eigenvalues().size(); ++i) mu.push_back(es.eigenvalues()[i]);
  std::sort(mu.begin(), mu.end(),
            [](const std::complex<double>& a, const std::complex<double>& b) { return std::abs(a) > std::abs(b); });
  return mu;
}

}  // namespace phasmid::continuation
