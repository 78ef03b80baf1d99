#include "continuation/shooting.hpp"

#include <algorithm>
#include <cstdio>
#include <cmath>

#include "common/error.hpp"

namespace phasmid::continuation {

CycleModel::CycleModel(const model::OdeModel& base, std::vector<double> y0, double t0)
    : sensitivity::InitialValueModel(base, std::move(y0), t0) {
  structure_ = base.structure();
  if (t0 == 0.0) set_triggers(base.triggers());
}

namespace {

// Output times of a cycle run: 0, each held phase's time fraction * T (sorted for the solver)
// and T last; held_index[j] is the output index of held phase j.
struct CycleOutputs {
  std::vector<double> t;
  std::vector<size_t> held_index;
};

CycleOutputs cycle_outputs(const std::vector<HeldPhase>& held, double T) {
  std::vector<std::pair<double, size_t>> at;
  for (size_t j = 0; j < held.size(); ++j) {
    if (!(held[j].fraction > 0 && held[j].fraction < 1))
      throw Error("held phase '" + held[j].name + "': its fraction of the period must lie in (0, 1)");
    at.push_back({held[j].fraction * T, j});
  }
  std::sort(at.begin(), at.end());
  CycleOutputs o{{0.0}, std::vector<size_t>(held.size())};
  for (const auto& [t, j] : at) o.held_index[j] = o.t.size(), o.t.push_back(t);
  o.t.push_back(T);
  return o;
}

// f(y(t_k)) of the cycle's run at output k, with the commands the run resolved up to `until`
// (the mode it was in there).
Eigen::VectorXd rhs_at(const CycleModel& cm, std::vector<double> pe, const solver::SolveResult& r, size_t k,
                       double until) {
  for (const auto& c : r.commands)
    if (c.t_ms <= until) pe[c.parameter] = c.t_ms;
  const size_t n = r.n_states;
  std::vector<double> y(n);
  for (size_t i = 0; i < n; ++i) y[i] = r.state(k, i);
  Eigen::VectorXd f(n);
  cm.rhs(r.t[k], y.data(), pe.data(), f.data());  // InitialValueModel adds t0
  return f;
}

}  // namespace

Shot shoot(const model::OdeModel& model, std::vector<double> p, const ParameterPath& path, const Cycle& cycle,
           const solver::SolverOptions& solver, const std::vector<HeldPhase>& held) {
  path.apply(p, cycle.parameter);
  CycleModel cm(model, cycle.y0, cycle.t0);
  const size_t n = model.num_states(), nb = cm.num_base_parameters();
  std::vector<size_t> sens;
  for (size_t i = 0; i < n; ++i) sens.push_back(nb + i);
  sens.insert(sens.end(), path.index.begin(), path.index.end());
  solver::SolverOptions so = solver;
  so.progress = false;
  so.sensitivities_at_outputs = true;
  const std::vector<double> pe = cm.extend(p);
  const CycleOutputs out = cycle_outputs(held, cycle.period_ms);
  const solver::SolveResult r = solver::Simulator(cm, so).run(pe, out.t, {}, sens);
  const size_t k = r.t.size() - 1;
  // d y_i(t_k) / d lambda along the path.
  auto dy_dlambda = [&](size_t kk, size_t i) {
    double d = 0.0;
    for (size_t j = 0; j < path.index.size(); ++j) d += path.slope[j] * r.sens(kk, i, n + j);
    return d;
  };
  Shot s;
  s.residual.resize(n);
  s.monodromy.resize(n, n);
  for (size_t i = 0; i < n; ++i) {
    s.residual[i] = r.state(k, i) - cycle.y0[i];
    for (size_t j = 0; j < n; ++j) s.monodromy(i, j) = r.sens(k, i, j) + (i == j ? 1.0 : 0.0);
  }
  if (!path.index.empty()) {
    s.dy_dparam.resize(n);
    for (size_t i = 0; i < n; ++i) s.dy_dparam[i] = dy_dlambda(k, i);
  }
  // f at the end of the cycle, in the mode the run ended in (every command it resolved).
  s.f_end = rhs_at(cm, pe, r, k, INFINITY);
  s.held_residual.resize(held.size());
  s.held_rows = Eigen::MatrixXd::Zero(held.size(), n + 2);
  for (size_t j = 0; j < held.size(); ++j) {
    const size_t kj = out.held_index[j], st = held[j].event.state;
    s.held_residual[j] = r.state(kj, st) - held[j].event.level;
    for (size_t i = 0; i < n; ++i) s.held_rows(j, i) = r.sens(kj, st, i) + (i == st ? 1.0 : 0.0);
    s.held_rows(j, n) = held[j].fraction * rhs_at(cm, pe, r, kj, r.t[kj])[st];  // t_j = fraction * T
    if (!path.index.empty()) s.held_rows(j, n + 1) = dy_dlambda(kj, st);
  }
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
  const CycleOutputs out = cycle_outputs(o.held_phases, cycle.period_ms);
  const solver::SolveResult r = solver::Simulator(cm, so).run(cm.extend(p), out.t);
  const size_t n = model.num_states(), k = r.t.size() - 1, m = o.held_phases.size();
  Eigen::VectorXd res(n + m);
  for (size_t i = 0; i < n; ++i) res[i] = r.state(k, i) - cycle.y0[i];
  for (size_t j = 0; j < m; ++j)
    res[n + j] = r.state(out.held_index[j], o.held_phases[j].event.state) - o.held_phases[j].event.level;
  return res;
}

std::vector<double> measure_fractions(const model::OdeModel& model, std::vector<double> p, const ParameterPath& path,
                                      const Cycle& cycle, const ShootingOptions& o) {
  path.apply(p, cycle.parameter);
  CycleModel cm(model, on_section(cycle.y0, o.section), cycle.t0);
  std::vector<solver::RootSpec> roots;
  for (const auto& h : o.held_phases) roots.push_back(h.event);
  solver::SolverOptions so = o.solver;
  so.progress = false;
  const solver::SolveResult r =
      solver::Simulator(cm, so).run(cm.extend(p), {0.0, cycle.period_ms}, aligned_roots(roots, o.section));
  std::vector<double> fractions;
  for (size_t j = 0; j < roots.size(); ++j) {
    double f = NAN;
    for (const auto& e : r.events)
      if (e.root == j && e.t > 0 && (roots[j].direction == 0 || e.direction == roots[j].direction)) {
        f = e.t / cycle.period_ms;
        break;
      }
    if (!(f > 0 && f < 1))
      throw Error("held phase '" + o.held_phases[j].name + "': its event does not occur within the cycle");
    fractions.push_back(f);
  }
  return fractions;
}

Eigen::MatrixXd newton_matrix(const Shot& s, size_t sec, const Eigen::VectorXd& row) {
  const Eigen::Index n = s.residual.size(), m = s.held_rows.rows();
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n + 2 + m, n + 2);
  J.topLeftCorner(n, n) = s.monodromy - Eigen::MatrixXd::Identity(n, n);
  J.block(0, n, n, 1) = s.f_end;
  if (s.dy_dparam.size() == n) J.block(0, n + 1, n, 1) = s.dy_dparam;
  J(n, static_cast<Eigen::Index>(sec)) = 1.0;
  if (m > 0) J.block(n + 1, 0, m, n + 2) = s.held_rows;
  J.row(n + 1 + m) = row.transpose();
  return J;
}

Eigen::VectorXd newton_step(const Eigen::MatrixXd& J, const Eigen::VectorXd& F, size_t neutral,
                            const Eigen::VectorXd& col_scale, const Eigen::VectorXd& row_scale) {
  if (neutral == 0 && J.rows() == J.cols()) return -J.colPivHouseholderQr().solve(F);
  const Eigen::VectorXd c = col_scale.size() == J.cols() ? col_scale : Eigen::VectorXd::Ones(J.cols());
  const Eigen::VectorXd r = row_scale.size() == J.rows() ? row_scale : Eigen::VectorXd::Ones(J.rows());
  const Eigen::MatrixXd A = r.asDiagonal() * J * c.asDiagonal();
  const Eigen::VectorXd b = r.cwiseProduct(F);
  if (neutral == 0) return -c.cwiseProduct(A.colPivHouseholderQr().solve(b));  // least squares
  Eigen::BDCSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::Index k = std::max<Eigen::Index>(0, A.cols() - static_cast<Eigen::Index>(neutral));
  const auto& sv = svd.singularValues();
  const Eigen::VectorXd coeff = (svd.matrixU().leftCols(k).transpose() * b).cwiseQuotient(sv.head(k));
  return -c.cwiseProduct(svd.matrixV().leftCols(k) * coeff);
}

Eigen::VectorXd row_scale(const ShootingOptions& o) {
  if (o.scale.size() == 0) return {};
  const Eigen::Index n = o.scale.size() - 2, m = static_cast<Eigen::Index>(o.held_phases.size());
  Eigen::VectorXd r = Eigen::VectorXd::Ones(n + 2 + m);
  r.head(n) = o.scale.head(n).cwiseInverse();
  r[n] = 1.0 / o.scale[static_cast<Eigen::Index>(o.section.state)];
  for (Eigen::Index j = 0; j < m; ++j) r[n + 1 + j] = 1.0 / o.scale[static_cast<Eigen::Index>(o.held_phases[j].event.state)];
  return r;
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
  // Rows: the cycle's n, the section, the held phases, the last row (row . (z - z_pred)).
  Eigen::VectorXd F(const Eigen::VectorXd& z) const {
    const size_t m = o.held_phases.size();
    Eigen::VectorXd f(n + 2 + m);
    const Eigen::VectorXd r = shooting_residual(model, p, path, cycle(z), o);
    ++report.plain_shots;
    f.head(n) = r.head(n);
    f[n] = z[o.section.state] - o.section.level;
    f.segment(n + 1, m) = r.tail(m);
    f[n + 1 + m] = row.dot(z - z_pred);
    return f;
  }
  Shot linearise(const Eigen::VectorXd& z) const {
    ++report.shots;
    return shoot(model, p, path, cycle(z), o.solver, o.held_phases);
  }
};

// The largest residual of the cycle's rows and the held phases' (state units): the section's
// and the last row are linear and solved exactly by each step.
double max_abs(const Eigen::VectorXd& f, size_t n) {
  if (!f.allFinite()) return INFINITY;
  const Eigen::Index m = f.size() - static_cast<Eigen::Index>(n) - 2;
  double r = f.head(static_cast<Eigen::Index>(n)).cwiseAbs().maxCoeff();
  if (m > 0) r = std::max(r, f.segment(static_cast<Eigen::Index>(n) + 1, m).cwiseAbs().maxCoeff());
  return r;
}

size_t worst_row(const Eigen::VectorXd& f, size_t n) {
  Eigen::Index worst = 0;
  f.head(f.size() - 1).cwiseAbs().maxCoeff(&worst);  // the last row is solved exactly
  return static_cast<size_t>(worst) == n ? 0 : static_cast<size_t>(worst);  // nor the section's
}

}  // namespace

Correction correct_cycle(const model::OdeModel& model, const std::vector<double>& p, const ParameterPath& path,
                         double t0, Eigen::VectorXd z, const Eigen::VectorXd& z_pred, const Eigen::VectorXd& row,
                         const ShootingOptions& o, NewtonReport& report, const Shot* start) {
  const size_t n = model.num_states(), sec = o.section.state;
  Correction out;
  report = {};
  Equations eq{model, p, path, t0, z_pred, row, o, report, n};
  z[sec] = o.section.level;
  Shot s;
  bool fresh = false;  // s is the linearisation at z
  Eigen::MatrixXd J;
  double gr = 1.0;
  size_t drop = 0;  // neutral directions of the last monodromy, left out of the steps
  const Eigen::VectorXd rs = row_scale(o);
  auto adopt = [&](Shot&& sh, bool at_z) {
    s = std::move(sh), fresh = at_z, J = newton_matrix(s, sec, row);
    const auto mu = multipliers(s.monodromy);
    gr = growth(mu);
    // Held phases pin the neutral directions; without them the steps drop them.
    drop = o.held_phases.empty() ? multiplier_roles(mu, o.neutral_tolerance).neutral.size() : 0;
  };
  auto relinearise = [&] { adopt(eq.linearise(z), true); };
  int slow = 0;  // consecutive fresh-monodromy steps that did not halve the residual
  if (start) adopt(Shot(*start), false);
  else relinearise();
  Eigen::VectorXd F = eq.F(z);
  for (int it = 0;; ++it) {
    const double res = max_abs(F, n);
    report.iterations = it;
    report.residual = res;
    report.worst_row = worst_row(F, n);
    if (o.on_iteration) o.on_iteration(it, res, report.worst_row, fresh);
    // Integration errors reach y(T) amplified by the largest multiplier (unstable cycles).
    if (res < o.tolerance * gr) {  // the section's and the row's equations are linear: solved exactly
      if (!fresh) s = eq.linearise(z);
      // The monodromy at z (for the multipliers) also gives one Newton step: it takes the
      // residual far below the tolerance where the cycle is weakly attracting (near a Hopf
      // point a residual at the tolerance is a much larger error in the state). The step is
      // O(tolerance): the monodromy at z stands for the one at the polished z.
      Eigen::VectorXd zn = z + newton_step(newton_matrix(s, sec, row), F, drop, o.scale, rs);
      zn[sec] = o.section.level;
      const Eigen::VectorXd Fn = eq.F(zn);
      if (max_abs(Fn, n) < res) z = zn, F = Fn, report.residual = max_abs(Fn, n);
      s.residual = F.head(n);
      s.held_residual = F.segment(n + 1, static_cast<Eigen::Index>(o.held_phases.size()));
      report.converged = true;
      out.z = z;
      out.shot = std::move(s);
      return out;
    }
    if (it >= o.max_iterations) break;
    Eigen::VectorXd dz = newton_step(J, F, drop, o.scale, rs);
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
    // Two steps in a row along Newton's own direction (a fresh monodromy) that did not halve
    // the residual: the guess is outside the region where the linearisation holds, and a
    // shorter continuation step is cheaper than more monodromies.
    slow = fresh && max_abs(Fn, n) > 0.5 * res ? slow + 1 : 0;
    if (slow >= 2) break;
    z = zn, F = Fn, fresh = false;
    if (max_abs(Fn, n) > 0.5 * res) relinearise();
  }
  out.z = z;
  out.shot = std::move(s);
  return out;
}

std::string row_name(const model::OdeModel& m, const ShootingOptions& o, size_t i) {
  const size_t n = m.num_states();
  if (i < n) return m.states().at(i).name;
  if (i > n && i - n - 1 < o.held_phases.size()) return "held phase " + o.held_phases[i - n - 1].name;
  return "section";
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
  ShootingOptions free = o;  // the member of a family the transient left: no held phase yet
  free.held_phases.clear();
  Cycle c = newton_fixed_parameter(model, p, {orbit.y0, orbit.period_ms, 0.0, t0}, free, report, shot);
  if (!report.converged) {
    char res[32];
    std::snprintf(res, sizeof res, "%.3g", report.residual);
    throw Error("Newton shooting did not converge from the cycle after the transient (residual " + std::string(res) +
                " in " + row_name(model, o, report.worst_row) + " after " + std::to_string(report.iterations) +
                " iterations)");
  }
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
