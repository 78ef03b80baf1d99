#include "continuation/cycle_sensitivity.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "common/error.hpp"
#include "features/features.hpp"
#include "io/h5_file.hpp"

namespace phasmid::continuation {
namespace {

// The cycle's model whose initial state follows the cycle's own dependence on the parameters:
// y0(p) = y0 + dy0/dp (p - p0) over the differentiated parameters. The solver's initial
// sensitivities (central differences of initial_state) then are dy0/dp exactly.
class CycleStartModel : public CycleModel {
 public:
  CycleStartModel(const model::OdeModel& base, const Cycle& c, const std::vector<size_t>& idx,
                  const std::vector<double>& p0, const Eigen::MatrixXd& dy0)
      : CycleModel(base, c.y0, c.t0), y0_(c.y0), idx_(idx), p0_(p0), dy0_(dy0) {}
  std::vector<double> initial_state(const std::vector<double>& p) const override {
    std::vector<double> y = y0_;
    for (size_t j = 0; j < idx_.size(); ++j) {
      const double d = p[idx_[j]] - p0_[idx_[j]];
      if (d != 0.0)
        for (size_t i = 0; i < y.size(); ++i) y[i] += dy0_(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) * d;
    }
    return y;
  }

 private:
  std::vector<double> y0_;
  std::vector<size_t> idx_;
  std::vector<double> p0_;
  Eigen::MatrixXd dy0_;
};

std::string section_name(const model::OdeModel& model, const solver::RootSpec& s) {
  char level[32];
  std::snprintf(level, sizeof level, "%g", s.level);
  return model.states().at(s.state).name + (s.direction < 0 ? " falling through " : " rising through ") + level;
}

// How far the orbit is from closing, from a plain run of `cycles` cycles after the transient:
// the spread (max - min) of the periods between its section crossings, and the return map's
// residual max_i |y_i(last crossing) - y_i(crossing before)| with the state where it is largest.
struct Closure {
  int cycles = 0;
  double period_spread_ms = NAN, residual = NAN;
  size_t worst = 0;
  std::string measure(const model::OdeModel& model) const {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "cycle-to-cycle period spread %.3g ms over %d cycles after the transient, return residual %.3g in ",
                  period_spread_ms, cycles, residual);
    return buf + model.states().at(worst).name;
  }
};

Closure closure(const model::OdeModel& model, const std::vector<double>& p, const ShootingOptions& o, int cycles) {
  solver::SolverOptions so = o.solver;
  so.progress = false;
  const solver::SolveResult r =
      solver::Simulator(model, so).run(p, {0.0, o.transient_ms + cycles * o.max_period_ms}, {o.section});
  std::vector<const solver::Event*> at;
  for (const auto& e : r.events)
    if (e.t >= o.transient_ms && (o.section.direction == 0 || e.direction == o.section.direction)) at.push_back(&e);
  Closure c;
  c.cycles = static_cast<int>(at.size()) - 1;
  if (at.size() < 2) return c;
  double lo = INFINITY, hi = -INFINITY;
  for (size_t k = 1; k < at.size(); ++k) lo = std::min(lo, at[k]->t - at[k - 1]->t), hi = std::max(hi, at[k]->t - at[k - 1]->t);
  c.period_spread_ms = hi - lo;
  const auto &a = at[at.size() - 2]->y, &b = at.back()->y;
  c.residual = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::abs(b[i] - a[i]) > c.residual) c.residual = std::abs(b[i] - a[i]), c.worst = i;
  return c;
}

// A model with commands at fixed times after the transient (a forced joint's switch schedule)
// is not autonomous: its cycle is pinned to the clock, and shooting from a section with a free
// period does not describe it (continuation/shooting.hpp, the contract of a cycle run).
void require_autonomous(const model::OdeModel& model, const std::vector<double>& p, const ShootingOptions& o) {
  for (double b : model.breakpoints(p, o.transient_ms + 2 * o.max_period_ms))
    if (b > o.transient_ms) {
      char at[32];
      std::snprintf(at, sizeof at, "%.6g", b);
      throw NoSteadyCycle("steady cycle: model " + model.kind() + " has commands at fixed times after the transient (at " + at +
                  " ms): its cycle is forced by the clock, not a free periodic orbit (mode = \"transient\" "
                  "differentiates the run instead)");
    }
}

// The cycle by Newton shooting. An orbit whose return map misses by more than 100 times
// Newton's tolerance after the transient (spikes that slip from cycle to cycle, no rhythm) is
// refused without trying Newton; one that Newton cannot close, after trying.
Cycle converge(const model::OdeModel& model, const std::vector<double>& p, const CycleSensitivityOptions& o,
               NewtonReport& report, Shot& shot) {
  require_autonomous(model, p, o.shooting);
  const std::string section = section_name(model, o.shooting.section);
  const Closure c = closure(model, p, o.shooting, 5);
  if (c.cycles < 2 || !(c.residual <= 100 * o.shooting.tolerance))
    throw NoSteadyCycle("steady cycle: the orbit does not close on the section " + section + ": " + c.measure(model) +
                " (mode = \"transient\" differentiates the run instead)");
  try {
    return find_cycle(model, p, o.shooting, report, &shot);
  } catch (const Error& e) {
    throw NoSteadyCycle("steady cycle: the orbit does not close on the section " + section + ": " + e.what() + "; " +
                c.measure(model) + " (mode = \"transient\" differentiates the run instead)");
  }
}

// dy(T)/dp_j at fixed y0 over one period of the cycle (states x parameters).
Eigen::MatrixXd period_sensitivities(const model::OdeModel& model, const std::vector<double>& p, const Cycle& c,
                                     const std::vector<size_t>& idx, solver::SolverOptions so) {
  CycleModel cm(model, c.y0, c.t0);
  so.progress = false;
  so.sensitivities_at_outputs = true;
  const solver::SolveResult r = solver::Simulator(cm, so).run(cm.extend(p), {0.0, c.period_ms}, {}, idx);
  const size_t n = model.num_states(), k = r.t.size() - 1;
  Eigen::MatrixXd s(n, idx.size());
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < idx.size(); ++j) s(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = r.sens(k, i, j);
  return s;
}

// The matrix of the implicit-function step, [Phi - I, f(y(T)); e_s^T, 0], factorised: its
// solve of [-dy(T)/dp; 0] gives dy0/dp (rows 0..n-1) and dT/dp (row n). A rank-deficient matrix
// (a family of cycles) has no unique answer.
using Factorisation = Eigen::ColPivHouseholderQR<Eigen::MatrixXd>;
Factorisation implicit_matrix(const model::OdeModel& model, const Shot& shot, size_t section,
                              const std::vector<std::complex<double>>& mu) {
  const auto n = static_cast<Eigen::Index>(model.num_states());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n + 1, n + 1);
  A.topLeftCorner(n, n) = shot.monodromy - Eigen::MatrixXd::Identity(n, n);
  A.topRightCorner(n, 1) = shot.f_end;
  A(n, static_cast<Eigen::Index>(section)) = 1.0;
  Factorisation qr(A);
  if (qr.rank() < n + 1) {
    std::string near;
    for (const auto& m : mu)
      if (std::abs(m - 1.0) < 1e-3) near += " " + std::to_string(m.real());
    throw NoSteadyCycle("steady cycle: the cycle belongs to a family (multipliers at 1:" + near +
                "), so its derivatives are not unique; differentiate the run with mode = \"transient\"");
  }
  return qr;
}

// The features on the converged cycle start at its section: no transient to discard.
features::FeatureOptions cycle_feature_options(const sensitivity::SensitivityOptions& opt) {
  features::FeatureOptions fo = opt.feature_options;
  fo.discard_ms = 0.0;
  fo.root_offset = 0;
  return fo;
}

// What one chunk of parameters gives (forward): dy0/dp and dT/dp (n + 1 rows), the features
// on the cycle and their gradients (features x chunk).
struct Chunk {
  Eigen::MatrixXd x;
  std::vector<features::Feature> features;
  Eigen::MatrixXd gradient;
  solver::SolverStats stats;
};

// The implicit-function columns of parameters idx: their period sensitivities solved for dy0/dp
// (rows 0..n-1) and dT/dp (row n).
Eigen::MatrixXd cycle_columns(const model::OdeModel& model, const std::vector<double>& p,
                              const sensitivity::SensitivityOptions& opt, const CycleSensitivityOptions& co,
                              const Cycle& cycle, const Factorisation& qr, const std::vector<size_t>& idx) {
  const auto n = static_cast<Eigen::Index>(model.num_states());
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(n + 1, static_cast<Eigen::Index>(idx.size()));
  b.topRows(n) = -period_sensitivities(model, p, cycle, idx, opt.solver);
  Eigen::MatrixXd x = qr.solve(b);
  x.row(static_cast<Eigen::Index>(co.shooting.section.state)).setZero();  // held on the section, exactly
  return x;
}

// The chunk's implicit-function columns, then with `features` the features and their gradients
// on feature_cycles periods of the cycle, started on the perturbed cycle (initial
// sensitivities dy0/dp).
Chunk forward_chunk(const model::OdeModel& model, const std::vector<double>& p, const sensitivity::SensitivityOptions& opt,
                    const CycleSensitivityOptions& co, const Cycle& cycle, const Factorisation& qr,
                    const std::vector<size_t>& idx, bool features) {
  const auto n = static_cast<Eigen::Index>(model.num_states());
  Chunk c;
  c.x = cycle_columns(model, p, opt, co, cycle, qr, idx);
  if (!features) return c;
  CycleStartModel sm(model, cycle, idx, p, c.x.topRows(n));
  const std::vector<double> pe = sm.extend(p);
  const double T = cycle.period_ms;
  solver::SolverOptions so = opt.solver;
  so.progress = false;
  so.sensitivities_at_outputs = false;  // the features need them at events only
  const solver::SolveResult r = solver::Simulator(sm, so).run(
      pe, solver::output_grid(co.feature_cycles * T, std::min(opt.output_dt_ms, T / 8.0)),
      aligned_roots(features::feature_roots(sm, pe), co.shooting.section), idx);
  const features::FeatureOptions fo = cycle_feature_options(opt);
  c.stats = r.stats;
  c.features = features::compute_features(sm, r, fo);
  c.gradient = Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(c.features.size()), static_cast<Eigen::Index>(idx.size()), NAN);
  for (const auto& g : features::compute_feature_gradients(sm, r, fo))
    for (size_t f = 0; f < c.features.size(); ++f)
      if (c.features[f].name == g.feature.name) c.gradient.row(static_cast<Eigen::Index>(f)) = g.gradient.transpose();
  return c;
}

// The analysis over chunks of parameters (sensitivity::for_each_chunk): dy0/dp and dT/dp, and
// with `features` the features' forward gradients. The chunks are fixed by the parameter list
// alone, so the numbers do not depend on the number of threads; the nominal features are the
// first chunk's.
void forward_chunks(const model::OdeModel& model, const std::vector<double>& p, const sensitivity::SensitivityOptions& opt,
                    const CycleSensitivityOptions& co, const Factorisation& qr, const std::vector<size_t>& idx,
                    bool features, CycleSensitivity& out) {
  const size_t per = std::max<size_t>(1, opt.chunk_parameters);
  std::vector<Chunk> chunks((idx.size() + per - 1) / per);
  sensitivity::for_each_chunk(idx.size(), opt, [&](size_t k, size_t begin, size_t end) {
    const std::vector<size_t> part(idx.begin() + static_cast<std::ptrdiff_t>(begin), idx.begin() + static_cast<std::ptrdiff_t>(end));
    chunks[k] = forward_chunk(model, p, opt, co, out.cycle, qr, part, features);
  });
  const auto n = static_cast<Eigen::Index>(model.num_states());
  out.dstate.resize(n, static_cast<Eigen::Index>(idx.size()));
  out.dperiod.resize(static_cast<Eigen::Index>(idx.size()));
  for (size_t k = 0; k < chunks.size(); ++k) {
    const auto c0 = static_cast<Eigen::Index>(k * per), m = chunks[k].x.cols();
    out.dstate.middleCols(c0, m) = chunks[k].x.topRows(n);
    out.dperiod.segment(c0, m) = chunks[k].x.row(n);
  }
  if (!features) return;
  auto& rep = out.report;
  rep.features = chunks[0].features;
  rep.stats = chunks[0].stats;
  rep.absolute = Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(rep.features.size()), static_cast<Eigen::Index>(idx.size()), NAN);
  for (size_t k = 0; k < chunks.size(); ++k)
    for (size_t f = 0; f < chunks[k].features.size(); ++f)
      for (size_t g = 0; g < rep.features.size(); ++g)
        if (rep.features[g].name == chunks[k].features[f].name)
          rep.absolute.block(static_cast<Eigen::Index>(g), static_cast<Eigen::Index>(k * per), 1, chunks[k].x.cols()) =
              chunks[k].gradient.row(static_cast<Eigen::Index>(f));
}

// Central differences of the converged cycle's features, Newton from the nominal cycle.
void cycle_feature_differences(const model::OdeModel& model, const std::vector<double>& p,
                               const sensitivity::SensitivityOptions& opt, const CycleSensitivityOptions& co,
                               const std::vector<size_t>& idx, CycleSensitivity& out) {
  auto& rep = out.report;
  rep.features = cycle_features(model, p, out.cycle, co);
  rep.absolute = Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(rep.features.size()),
                                           static_cast<Eigen::Index>(idx.size()), NAN);
  auto value = [](const std::vector<features::Feature>& fs, const std::string& name) {
    for (const auto& f : fs)
      if (f.name == name) return f.value;
    return static_cast<double>(NAN);
  };
  for (size_t j = 0; j < idx.size(); ++j) {
    const double h = opt.fd_relative_step * std::max(std::abs(p[idx[j]]), opt.fd_min_scale);
    std::vector<double> pp = p, pm = p;
    pp[idx[j]] += h, pm[idx[j]] -= h;
    std::vector<features::Feature> fp, fm;
    try {
      fp = cycle_features(model, pp, out.cycle, co), fm = cycle_features(model, pm, out.cycle, co);
    } catch (const Error& e) {
      throw Error("steady cycle: central difference by " + rep.parameters[j] + " (step " + std::to_string(h) +
                  "): " + e.what());
    }
    rep.fd_runs += 2;
    for (size_t f = 0; f < rep.features.size(); ++f)
      rep.absolute(static_cast<Eigen::Index>(f), static_cast<Eigen::Index>(j)) =
          (value(fp, rep.features[f].name) - value(fm, rep.features[f].name)) / (2 * h);
  }
}

}  // namespace

CycleSensitivityOptions default_cycle_options(const model::OdeModel& model) {
  CycleSensitivityOptions o;
  o.shooting.section = sensitivity::default_section(model);
  return o;
}

std::vector<features::Feature> cycle_features(const model::OdeModel& model, const std::vector<double>& p,
                                              const Cycle& guess, const CycleSensitivityOptions& o) {
  // Newton from the guess (the nominal cycle, for a difference quotient); where it cannot
  // close the cycle from there, the cycle the run reaches after the transient.
  NewtonReport report;
  Cycle c;
  try {
    c = newton_fixed_parameter(model, p, guess, o.shooting, report);
  } catch (const Error&) {
    report.converged = false;
  }
  if (!report.converged) c = find_cycle(model, p, o.shooting, report);
  CycleModel cm(model, on_section(c.y0, o.shooting.section), c.t0);
  const std::vector<double> pe = cm.extend(p);
  solver::SolverOptions so = o.shooting.solver;
  so.progress = false;
  const solver::SolveResult r =
      solver::Simulator(cm, so).run(pe, solver::output_grid(o.feature_cycles * c.period_ms, c.period_ms / 8.0),
                                    aligned_roots(features::feature_roots(cm, pe), o.shooting.section));
  return features::compute_features(cm, r, {});
}

CycleSensitivity analyse_cycle_sensitivities(const model::OdeModel& model, const std::vector<double>& p,
                                             const sensitivity::SensitivityOptions& options,
                                             CycleSensitivityOptions co) {
  const auto wall0 = std::chrono::steady_clock::now();
  sensitivity::SensitivityOptions opt = options;
  if (opt.solver.rtol > co.max_rtol) {
    opt.solver.atol *= co.max_rtol / opt.solver.rtol;
    opt.solver.rtol = co.max_rtol;
  }
  co.shooting.solver = opt.solver;
  co.shooting.solver.progress = false;
  const std::vector<size_t> idx = sensitivity::select_parameters(model, opt.parameters);
  CycleSensitivity out;
  auto& rep = out.report;
  rep = sensitivity::report_header(model, p, idx, opt);
  Shot shot;
  out.cycle = converge(model, p, co, out.newton, shot);
  out.cycle.y0 = on_section(out.cycle.y0, co.shooting.section);
  out.section = section_name(model, co.shooting.section);
  out.residual = out.newton.residual;
  out.multipliers = multipliers(shot.monodromy);
  const Factorisation qr = implicit_matrix(model, shot, co.shooting.section.state, out.multipliers);
  const bool forward = opt.method == sensitivity::Method::Forward;
  forward_chunks(model, p, opt, co, qr, idx, forward, out);  // dy0/dp and dT/dp in either method
  if (!forward) cycle_feature_differences(model, p, opt, co, idx, out);
  sensitivity::rank_parameters(rep);
  rep.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return out;
}

void write_cycle_h5(io::H5Writer& out, const model::OdeModel& model, const CycleSensitivity& r) {
  const std::string g = "/sensitivity/cycle";
  out.ensure_group(g);
  const size_t n = model.num_states(), np = static_cast<size_t>(r.dperiod.size());
  out.write(g + "/period_ms", std::vector<double>{r.cycle.period_ms}, "ms");
  out.write(g + "/dperiod", std::vector<double>(r.dperiod.data(), r.dperiod.data() + np),
            "ms per parameter unit (parameters: /sensitivity/parameters)");
  out.write(g + "/state_on_section", r.cycle.y0, "state units (/sensitivity/cycle/state_names)");
  std::vector<std::string> names;
  for (const auto& s : model.states()) names.push_back(s.name);
  out.write(g + "/state_names", names);
  std::vector<double> d(n * np);
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < np; ++j) d[i * np + j] = r.dstate(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
  out.write(g + "/dstate", d, "state unit per parameter unit", {n, np});
  std::vector<double> re, im, ab;
  for (const auto& m : r.multipliers) re.push_back(m.real()), im.push_back(m.imag()), ab.push_back(std::abs(m));
  out.write(g + "/multipliers_real", re, "1");
  out.write(g + "/multipliers_imag", im, "1");
  out.write(g + "/multipliers_abs", ab, "1");
  out.set_attribute(g, "residual", r.residual);
  out.set_attribute(g, "section", r.section);
  out.set_attribute(g, "newton_iterations", static_cast<double>(r.newton.iterations));
}

}  // namespace phasmid::continuation
