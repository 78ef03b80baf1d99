#include "sensitivity/sensitivity.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

#include "common/error.hpp"
#include "io/h5_file.hpp"
#include "parallel/executor.hpp"

namespace phasmid::sensitivity {

Method parse_method(const std::string& s) {
  if (s == "forward") return Method::Forward;
  if (s == "fd") return Method::FiniteDifference;
  throw Error("unknown sensitivity method '" + s + "' (expected forward or fd)");
}

const char* method_name(Method m) { return m == Method::Forward ? "forward" : "fd"; }

size_t SensitivityReport::feature_index(const std::string& name) const {
  for (size_t i = 0; i < features.size(); ++i)
    if (features[i].name == name) return i;
  throw Error("no feature '" + name + "' in the sensitivity report");
}

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

struct FdColumn {
  std::vector<double> dfeature;  // per nominal feature (NaN if missing in a perturbed run)
  std::vector<double> dy;        // n_time x n_states
};

FdColumn fd_column(const solver::Simulator& sim, const std::vector<double>& p, size_t k, const std::vector<double>& grid,
                   const model::OdeModel& model,
                   const features::FeatureOptions& fopt, const std::vector<features::Feature>& nominal,
                   const SensitivityOptions& opt, long& runs) {
  const double h = opt.fd_relative_step * std::max(std::abs(p[k]), opt.fd_min_scale);
  std::vector<double> pp = p, pm = p;
  pp[k] += h;
  pm[k] -= h;
  // Crossing levels that are parameters (contact threshold, CPG activity level) move too.
  solver::SolveResult rp = sim.run(pp, grid, features::feature_roots(model, pp)),
                      rm = sim.run(pm, grid, features::feature_roots(model, pm));
  runs += 2;
  auto fp = features::compute_features(model, rp, fopt), fm = features::compute_features(model, rm, fopt);
  auto find = [](const std::vector<features::Feature>& fs, const std::string& name) {
    for (auto& f : fs)
      if (f.name == name) return f.value;
    return kNaN;
  };
  FdColumn col;
  for (auto& f : nominal) col.dfeature.push_back((find(fp, f.name) - find(fm, f.name)) / (2 * h));
  if (opt.write_trajectory) {
    col.dy.resize(rp.y.size());
    for (size_t i = 0; i < rp.y.size(); ++i) col.dy[i] = (rp.y[i] - rm.y[i]) / (2 * h);
  }
  return col;
}

}  // namespace

std::vector<size_t> select_parameters(const model::OdeModel& model, const std::vector<std::string>& names) {
  const auto& ps = model.parameters();
  std::vector<size_t> idx;
  // Command times set by [[triggers]] are functions of the other parameters (event time plus a
  // delay), not free parameters: left out of "all", an error if named (docs/sensitivity.md).
  std::vector<std::string> triggered_by(ps.size());
  for (const auto& tr : model.triggers())
    for (size_t q : tr.targets) triggered_by[q] = tr.event;
  if (names.empty()) {
    for (size_t k = 0; k < ps.size(); ++k)
      if (triggered_by[k].empty()) idx.push_back(k);
  } else {
    for (auto& name : names) {
      idx.push_back(ps.index(name));  // throws naming an unknown parameter
      if (!triggered_by[idx.back()].empty())
        throw Error("no sensitivity to " + name + ": it is set by the [[triggers]] event " + triggered_by[idx.back()] +
                    " (give it a fixed value to differentiate by it)");
    }
  }
  if (idx.empty()) throw Error("sensitivity analysis needs at least one parameter");
  return idx;
}

void rank_parameters(SensitivityReport& rep) {
  const size_t nf = rep.features.size(), np = rep.parameters.size();
  rep.relative = Eigen::MatrixXd::Constant(nf, np, kNaN);
  for (size_t f = 0; f < nf; ++f) {
    const double F = rep.features[f].value;
    for (size_t j = 0; j < np; ++j)
      if (F != 0.0) rep.relative(f, j) = rep.parameter_values[j] / F * rep.absolute(f, j);
    std::vector<size_t> order(np);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
      double ra = std::abs(rep.relative(f, a)), rb = std::abs(rep.relative(f, b));
      if (std::isnan(ra)) return false;
      if (std::isnan(rb)) return true;
      return ra > rb;
    });
    std::vector<std::string> names;
    for (size_t j : order) names.push_back(rep.parameters[j]);
    rep.ranking.push_back(std::move(names));
  }
}

namespace {

// One chunk of forward columns: its run (the first chunk's is the nominal run) and the
// features' gradients by its parameters.
struct ForwardChunk {
  std::vector<size_t> cols;  // report columns
  solver::SolveResult run;
  std::vector<features::FeatureGradient> gradients;
};

// The forward columns in chunks (for_each_chunk), each chunk one run with its sensitivities.
// At least one chunk (without columns: the plain nominal run).
std::vector<ForwardChunk> forward_chunks(const model::OdeModel& model, const std::vector<double>& p,
                                         const std::vector<size_t>& idx, const std::vector<size_t>& fwd_cols,
                                         const SensitivityOptions& opt, const std::vector<double>& grid,
                                         const std::vector<solver::RootSpec>& roots, const features::FeatureOptions& fopt) {
  const size_t per = std::max<size_t>(1, opt.chunk_parameters);
  std::vector<ForwardChunk> chunks(std::max<size_t>(1, (fwd_cols.size() + per - 1) / per));
  solver::SolverOptions sopt = opt.solver;
  sopt.sensitivities_at_outputs = opt.write_trajectory;  // the features need them at events only
  sopt.progress = opt.solver.progress && chunks.size() == 1;  // one bar, not several at once
  auto run = [&](size_t k, size_t begin, size_t end) {
    ForwardChunk& c = chunks[k];
    std::vector<size_t> params;
    for (size_t j = begin; j < end; ++j) c.cols.push_back(fwd_cols[j]), params.push_back(idx[fwd_cols[j]]);
    // Parameters that move a switch time or the initial state are handled by the solver
    // (initial sensitivities dy0/dp and jump conditions at parameter-dependent switches).
    c.run = solver::Simulator(model, sopt).run(p, grid, roots, params);
    if (!params.empty()) c.gradients = features::compute_feature_gradients(model, c.run, fopt);
  };
  if (for_each_chunk(fwd_cols.size(), opt, run) == 0) run(0, 0, 0);
  return chunks;
}

}  // namespace

SensitivityReport report_header(const model::OdeModel& model, const std::vector<double>& p,
                                const std::vector<size_t>& idx, const SensitivityOptions& opt) {
  SensitivityReport rep;
  rep.method = opt.method;
  rep.rtol = opt.solver.rtol;
  rep.atol = opt.solver.atol;
  rep.tolerance_factor = opt.method == Method::Forward ? opt.solver.sensitivity_tolerance_factor : 1.0;
  for (size_t k : idx) {
    const auto& par = model.parameters().at(k);
    rep.parameters.push_back(par.name);
    rep.parameter_units.push_back(par.unit);
    rep.parameter_values.push_back(p[k]);
    rep.parameter_method.push_back(method_name(opt.method));
  }
  return rep;
}

size_t for_each_chunk(size_t count, const SensitivityOptions& opt,
                      const std::function<void(size_t chunk, size_t begin, size_t end)>& run) {
  const size_t per = std::max<size_t>(1, opt.chunk_parameters), nc = (count + per - 1) / per;
  std::vector<parallel::Task> tasks(nc);
  for (size_t k = 0; k < nc; ++k) tasks[k].id = k;
  const bool progress = opt.solver.progress && nc > 1;
  size_t done = 0;
  // Threads share this process's memory: each call fills its own chunk, no bytes travel.
  parallel::make_openmp_executor(parallel::bounded_threads(opt.threads))->run(tasks, [&](const parallel::Task& t, int) {
    run(t.id, t.id * per, std::min(count, (t.id + 1) * per));
    return std::string();
  }, [&](size_t, std::string) {
    if (progress)
      std::fprintf(stderr, "\r%s: %zu of %zu parameters", opt.solver.progress_label.c_str(), std::min(count, ++done * per),
                   count);
  }, [] { return true; });
  if (progress) std::fprintf(stderr, "\n");
  return nc;
}

SensitivityReport analyse_sensitivities(const model::OdeModel& model, std::vector<double> p,
                                        const SensitivityOptions& opt) {
  auto wall0 = std::chrono::steady_clock::now();
  const auto& ps = model.parameters();
  if (p.size() != ps.size()) throw Error("internal: parameter vector size mismatch");
  const std::vector<size_t> idx = select_parameters(model, opt.parameters);
  SensitivityReport rep = report_header(model, p, idx, opt);
  const size_t np = idx.size(), n = model.num_states();

  const std::vector<double> grid = solver::output_grid(opt.t_end_ms, opt.output_dt_ms);
  const std::vector<solver::RootSpec> roots = features::feature_roots(model, p);
  features::FeatureOptions fopt = opt.feature_options;
  fopt.discard_ms = opt.discard_ms;
  fopt.root_offset = 0;

  // Columns done by forward sensitivities, the rest by finite differences.
  std::vector<size_t> fwd_cols, fd_cols;
  for (size_t j = 0; j < np; ++j) (opt.method == Method::FiniteDifference ? fd_cols : fwd_cols).push_back(j);
  const std::vector<ForwardChunk> chunks = forward_chunks(model, p, idx, fwd_cols, opt, grid, roots, fopt);
  const solver::SolveResult& nominal = chunks[0].run;
  rep.stats = nominal.stats;
  rep.features = features::compute_features(model, nominal, fopt);
  const size_t nf = rep.features.size();
  rep.absolute = Eigen::MatrixXd::Constant(nf, np, kNaN);
  rep.time = nominal.t;
  for (auto& s : model.states()) {
    rep.state_names.push_back(s.name);
    rep.state_units.push_back(s.unit);
  }
  rep.states = nominal.y;
  const size_t nt = nominal.t.size();
  if (opt.write_trajectory) rep.trajectory.assign(nt * n * np, 0.0);

  for (const ForwardChunk& ch : chunks) {
    // Every feature of compute_features has a forward gradient (gait_class a zero one); a
    // feature the gradient pass does not produce would keep NaN.
    for (const auto& g : ch.gradients) {
      const size_t f = rep.feature_index(g.feature.name);
      for (size_t c = 0; c < ch.cols.size(); ++c) rep.absolute(f, ch.cols[c]) = g.gradient[c];
    }
    if (opt.write_trajectory && !ch.cols.empty())
      for (size_t k = 0; k < nt; ++k)
        for (size_t i = 0; i < n; ++i)
          for (size_t c = 0; c < ch.cols.size(); ++c) rep.trajectory[(k * n + i) * np + ch.cols[c]] = ch.run.sens(k, i, c);
  }
  solver::SolverOptions sopt = opt.solver;
  sopt.sensitivities_at_outputs = opt.write_trajectory;
  const solver::Simulator sim(model, sopt);
  for (size_t j : fd_cols) {
    FdColumn col = fd_column(sim, p, idx[j], grid, model, fopt, rep.features, opt, rep.fd_runs);
    for (size_t f = 0; f < nf; ++f) rep.absolute(f, j) = col.dfeature[f];
    if (opt.write_trajectory) {
      if (col.dy.size() != nt * n) throw Error("internal: finite-difference trajectory has a different length");
      for (size_t k = 0; k < nt; ++k)
        for (size_t i = 0; i < n; ++i) rep.trajectory[(k * n + i) * np + j] = col.dy[k * n + i];
    }
  }

  rank_parameters(rep);
  rep.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return rep;
}

void write_sensitivity_h5(io::H5Writer& out, const SensitivityReport& rep) {
  const size_t np = rep.parameters.size();
  out.ensure_group("/sensitivity");
  out.set_attribute("/sensitivity", "method", std::string(method_name(rep.method)));
  out.set_attribute("/sensitivity", "rtol", rep.rtol);
  out.set_attribute("/sensitivity", "atol", rep.atol);
  out.set_attribute("/sensitivity", "tolerance_factor", rep.tolerance_factor);
  out.write("/sensitivity/parameters", rep.parameters);
  out.write("/sensitivity/parameter_units", rep.parameter_units);
  out.write("/sensitivity/parameter_method", rep.parameter_method);
  out.write("/sensitivity/parameter_values", rep.parameter_values, "see /sensitivity/parameter_units");
  std::vector<std::string> fnames, funits;
  std::vector<double> fvalues;
  for (auto& f : rep.features) {
    fnames.push_back(f.name);
    funits.push_back(f.unit);
    fvalues.push_back(f.value);
  }
  out.write("/sensitivity/feature_names", fnames);
  out.write("/sensitivity/feature_units", funits);
  out.write("/sensitivity/feature_values", fvalues, "see /sensitivity/feature_units");
  for (size_t f = 0; f < rep.features.size(); ++f) {
    const auto& feat = rep.features[f];
    std::vector<double> abs(np), rel(np);
    std::vector<std::string> units(np);
    for (size_t j = 0; j < np; ++j) {
      abs[j] = rep.absolute(f, j);
      rel[j] = rep.relative(f, j);
      units[j] = feat.unit + "/(" + rep.parameter_units[j] + ")";
    }
    const std::string path = "/sensitivity/features/" + feat.name;
    out.write(path, abs, feat.unit + " per parameter unit (per parameter: /sensitivity/units/" + feat.name + ")");
    out.set_attribute(path, "feature_value", feat.value);
    out.set_attribute(path, "feature_unit", feat.unit);
    out.write("/sensitivity/units/" + feat.name, units);
    out.write("/sensitivity/relative/" + feat.name, rel, "1");
    out.write("/sensitivity/ranking/" + feat.name, rep.ranking[f]);
  }
  if (!rep.trajectory.empty()) {
    out.write("/sensitivity/time", rep.time, "ms");
    out.write("/sensitivity/state_names", rep.state_names);
    out.write("/sensitivity/state_units", rep.state_units);
    out.write("/sensitivity/trajectory", rep.trajectory,
              "state unit per parameter unit (states as integrated: /sensitivity/state_units)",
              {rep.time.size(), rep.state_names.size(), np});
  }
}

}  // namespace phasmid::sensitivity
