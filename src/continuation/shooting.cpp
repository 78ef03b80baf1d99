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

Eigen::VectorXd shooting_residual(const model::OdeModel& model, std::vector<double> p, const ParameterPath& path,
                                  const Cycle& cycle, const ShootingOptions& o) {
  path.apply(p, cycle.parameter);
  CycleModel cm(model, cycle.y0, cycle.t0);
  solver::SolverOptions so = o.solver;
  so.progress = false;
  if (o.residual_rtol > 0) {
    so.atol *= o.residual_rtol / so.rtol;
    so.rtol = o.residual_rtol;
  }
  const solver::SolveResult r = solver::Simulator(cm, so).run(cm.extend(p), {0.0, cycle.period_ms});
  const size_t n = model.num_states(), k = r.t.size() - 1;
  Eigen::VectorXd res(n);
  for (size_t i = 0; i < n; ++i) res[i] = r.state(k, i) - cycle.y0[i];
  return res;
}

Eigen::MatrixXd newton_matrix(const Shot& s, size_t sec, const Eigen::VectorXd& row) {
  const Eigen::Index n = s.residual.size();
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n + 2, n + 2);
  J.topLeftCorner(n, n) = s.monodromy - Eigen::MatrixXd::Identity(n, n);
  J.block(0, n, n, 1) = s.f_end;
  if (s.dy_dparam.size() == n) J.block(0, n + 1, n, 1) = s.dy_dparam;
  J(n, static_cast<Eigen::Index>(sec)) = 1.0;
  J.row(n + 1) = row.transpose();
  return J;
}

Eigen::VectorXd newton_step(const Eigen::MatrixXd& J, const Eigen::VectorXd& F, size_t neutral,
                            const Eigen::VectorXd& scale, size_t section_state) {
  if (neutral == 0) return -J.colPivHouseholderQr().solve(F);
  const Eigen::Index m = J.rows();
  const Eigen::VectorXd c = scale.size() == J.cols() ? scale : Eigen::VectorXd::Ones(J.cols());
  Eigen::VectorXd r = Eigen::VectorXd::Ones(m);  // 1 / typical size of each row's residual
  for (Eigen::Index i = 0; i + 2 < m; ++i) r[i] = 1.0 / c[i];
  r[m - 2] = 1.0 / c[static_cast<Eigen::Index>(section_state)];
  const Eigen::MatrixXd A = r.asDiagonal() * J * c.asDiagonal();
  Eigen::BDCSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::Index k = std::max<Eigen::Index>(0, A.cols() - static_cast<Eigen::Index>(neutral));
  const auto& sv = svd.singularValues();
  const Eigen::VectorXd coeff = (svd.matrixU().leftCols(k).transpose() * r.cwiseProduct(F)).cwiseQuotient(sv.head(k));
  return -c.cwiseProduct(svd.matrixV().leftCols(k) * coeff);
}

MultiplierRoles multiplier_roles(const std::vector<std::complex<double>>& mu, double neutral_tolerance) {
  MultiplierRoles r;
  for (size_t i = 1; i < mu.size(); ++i)
    if (std::abs(mu[i] - 1.0) < std::abs(mu[r.trivial] - 1.0)) r.trivial = i;
  for (size_t i = 0; i < mu.size(); ++i)
    if (i != r.trivial && std::abs(mu[i] - 1.0) < neutral_tolerance) r.neutral.push_back(i);
  return r;
}

std::vector<double> on_section(std::vector<double> y0, const solver::RootSpec& section) {
  y0[section.state] = section.level;
  return y0;
}

std::vector<solver::RootSpec> aligned_roots(std::vector<solver::RootSpec> roots, const solver::RootSpec& section) {
  for (auto& r : roots)
    if (r.state == section.state && std::abs(r.level - section.level) <= 1e-12 * std::max(1.0, std::abs(section.level)))
      r.level = section.level;
  return roots;
}

namespace {

// The cycle equations' residual F(z) (n + 2 rows) and its linearisation, with the counters.
struct Equations {
  const model::OdeModel& model;
  const std::vector<double>& p;
  const ParameterPath& path;
  double t0;
  const Eigen::VectorXd& z_pred;
  const Eigen::VectorXd& row;
  const ShootingOptions& o;
  NewtonReport& report;
  size_t n;

  Cycle cycle(const Eigen::VectorXd& z) const {
    return {std::vector<double>(z.data(), z.data() + n), z[n], z.size() > static_cast<Eigen::Index>(n + 1) ? z[n + 1] : 0.0, t0};
  }
  Eigen::VectorXd F(const Eigen::VectorXd& z) const {
    Eigen::VectorXd f(n + 2);
    f.head(n) = shooting_residual(model, p, path, cycle(z), o);
    ++report.plain_shots;
    f[n] = z[o.section.state] - o.section.level;
    f[n + 1] = row.dot(z - z_pred);
    return f;
  }
  Shot linearise(const Eigen::VectorXd& z) const {
    ++report.shots;
    return shoot(model, p, path, cycle(z), o.solver);
  }
};

double max_abs(const Eigen::VectorXd& f, size_t n) {
  const double m = f.head(static_cast<Eigen::Index>(n)).cwiseAbs().maxCoeff();
  return std::isfinite(m) ? m : INFINITY;
}

}  // namespace

Correction correct_cycle(const model::OdeModel& model, const std::vector<double>& p, const ParameterPath& path,
                         double t0, Eigen::VectorXd z, const Eigen::VectorXd& z_pred, const Eigen::VectorXd& row,
                         const ShootingOptions& o, NewtonReport& report) {
  const size_t n = model.num_states(), sec = o.section.state;
  Correction out;
  report = {};
  Equations eq{model, p, path, t0, z_pred, row, o, report, n};
  z[sec] = o.section.level;
  Shot s;
  bool fresh = false;  // s is the linearisation at z
  Eigen::MatrixXd J;
  double gr = 1.0;
  size_t neutral = 0;  // neutral directions of the last monodromy, left out of the steps
  auto relinearise = [&] {
    s = eq.linearise(z), fresh = true, J = newton_matrix(s, sec, row);
    const auto mu = multipliers(s.monodromy);
    gr = growth(mu);
    neutral = multiplier_roles(mu, o.neutral_tolerance).neutral.size();
  };
  relinearise();
  Eigen::VectorXd F = eq.F(z);
  for (int it = 0;; ++it) {
    const double res = max_abs(F, n);
    report.iterations = it;
    report.residual = res;
    if (o.on_iteration) o.on_iteration(it, res, fresh);
    // Integration errors reach y(T) amplified by the largest multiplier (unstable cycles).
    if (res < o.tolerance * gr) {  // the section's and the row's equations are linear: solved exactly
      if (!fresh) s = eq.linearise(z);
      // The monodromy at z (for the multipliers) also gives one Newton step: it takes the
      // residual far below the tolerance where the cycle is weakly attracting (near a Hopf
      // point a residual at the tolerance is a much larger error in the state). The step is
      // O(tolerance): the monodromy at z stands for the one at the polished z.
      Eigen::VectorXd zn = z + newton_step(newton_matrix(s, sec, row), F, neutral, o.scale, sec);
      zn[sec] = o.section.level;
      const Eigen::VectorXd Fn = eq.F(zn);
      if (max_abs(Fn, n) < res) z = zn, F = Fn, report.residual = max_abs(Fn, n);
      s.residual = F.head(n);
      report.converged = true;
      out.z = z;
      out.shot = std::move(s);
      return out;
    }
    if (it >= o.max_iterations) break;
    Eigen::VectorXd dz = newton_step(J, F, neutral, o.scale, sec);
    Eigen::VectorXd zn, Fn;
    int halvings = 0;
    for (;; ++halvings, dz *= 0.5) {
      zn = z + dz;
      zn[sec] = o.section.level;
      if (!(zn[n] > 0.0)) zn[n] = 0.5 * z[n];
      Fn = eq.F(zn);
      if (max_abs(Fn, n) <= res || halvings >= 4) break;
    }
    if (!(max_abs(Fn, n) <= res)) {
      if (fresh) break;  // no descent along Newton's own direction
      relinearise();
      continue;
    }
    const Eigen::VectorXd step = zn - z;
    if (step.squaredNorm() > 0) J += ((Fn - F) - J * step) * step.transpose() / step.squaredNorm();  // Broyden's update
    z = zn, F = Fn, fresh = false;
    if (max_abs(Fn, n) > 0.5 * res) relinearise();
  }
  out.z = z;
  out.shot = std::move(s);
  return out;
}

Cycle newton_fixed_parameter(const model::OdeModel& model, const std::vector<double>& p, const Cycle& guess,
                             const ShootingOptions& o, NewtonReport& report, Shot* shot_out) {
  const size_t n = model.num_states();
  Eigen::VectorXd z(n + 2), row = Eigen::VectorXd::Zero(n + 2);
  for (size_t i = 0; i < n; ++i) z[i] = guess.y0[i];
  z[n] = guess.period_ms;
  z[n + 1] = guess.parameter;
  row[n + 1] = 1.0;
  Correction c = correct_cycle(model, p, {}, guess.t0, z, z, row, o, report);
  if (shot_out && report.converged) *shot_out = std::move(c.shot);
  return {std::vector<double>(c.z.data(), c.z.data() + n), c.z[n], guess.parameter, guess.t0};
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

double growth(const std::vector<std::complex<double>>& mu) {
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
