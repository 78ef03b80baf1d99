#include "sensitivity/segmented.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "common/error.hpp"

namespace phasmid::sensitivity {
namespace {

// One segment [t0, t1] of the base model between breakpoints, started at y_start, with the
// state shifted by S (p - pbar) over the sensitivity parameters.
class SegmentModel : public model::OdeModelT<SegmentModel> {
 public:
  SegmentModel(const model::OdeModel& base, std::vector<double> y_start, double t0, std::vector<double> pbar,
               std::vector<size_t> sens, Eigen::MatrixXd S)
      : base_(base), y_start_(std::move(y_start)), t0_(t0), pbar_(std::move(pbar)), sens_(std::move(sens)), S_(std::move(S)) {
    for (const auto& par : base.parameters().all()) params_.add(par);
    for (const auto& s : base.states()) add_state(s.name, s.unit);
    angles_ = base.angles();
  }
  std::string kind() const override { return base_.kind(); }
  std::vector<double> initial_state(const std::vector<double>&) const override { return y_start_; }
  int jacobian_half_bandwidth() const override { return base_.jacobian_half_bandwidth(); }
  template <class T>
  void eval(double t, const T* x, const T* p, T* xdot) const {
    thread_local std::vector<T> y;
    const size_t n = num_states();
    y.assign(x, x + n);
    for (size_t c = 0; c < sens_.size(); ++c) {
      T dp = p[sens_[c]] - pbar_[sens_[c]];
      for (size_t i = 0; i < n; ++i)
        if (S_(i, c) != 0.0) y[i] += S_(i, c) * dp;
    }
    base_.rhs(t0_ + t, y.data(), p, xdot);
  }

 private:
  const model::OdeModel& base_;
  std::vector<double> y_start_;
  double t0_;
  std::vector<double> pbar_;
  std::vector<size_t> sens_;
  Eigen::MatrixXd S_;
};

std::vector<double> sorted_breaks(const model::OdeModel& m, const std::vector<double>& p, double t_end) {
  std::vector<double> b = m.breakpoints(p, t_end);
  std::sort(b.begin(), b.end());
  b.erase(std::remove_if(b.begin(), b.end(), [&](double x) { return x <= 0.0 || x >= t_end; }), b.end());
  b.erase(std::unique(b.begin(), b.end()), b.end());
  return b;
}

}  // namespace

solver::SolveResult run_with_switch_sensitivities(const model::OdeModel& model, const std::vector<double>& p,
                                                  const std::vector<double>& output_times,
                                                  const std::vector<solver::RootSpec>& roots,
                                                  const std::vector<size_t>& sens_params,
                                                  const solver::SolverOptions& options) {
  const size_t n = model.num_states(), ns = sens_params.size();
  if (output_times.empty() || output_times.front() < 0) throw Error("output times must start at t >= 0");
  const double t_end = output_times.back();

  // dy0/dp and dtau_k/dp by central differences of the algebraic functions.
  std::vector<double> y = model.initial_state(p);
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(n, ns);
  const std::vector<double> taus = sorted_breaks(model, p, t_end);
  Eigen::MatrixXd dtau = Eigen::MatrixXd::Zero(taus.size(), ns);
  for (size_t c = 0; c < ns; ++c) {
    const size_t k = sens_params[c];
    const double h = 1e-6 * std::max(std::abs(p[k]), 1e-3);
    std::vector<double> pp = p, pm = p;
    pp[k] += h;
    pm[k] -= h;
    std::vector<double> a = model.initial_state(pp), b = model.initial_state(pm);
    for (size_t i = 0; i < n; ++i) S(i, c) = (a[i] - b[i]) / (2 * h);
    std::vector<double> bp = sorted_breaks(model, pp, 2 * t_end + 1), bm = sorted_breaks(model, pm, 2 * t_end + 1);
    if (bp.size() < taus.size() || bm.size() < taus.size())
      throw Error("switch times of the model change in number with parameter " + model.parameters().at(k).name);
    for (size_t j = 0; j < taus.size(); ++j) dtau(j, c) = (bp[j] - bm[j]) / (2 * h);
  }

  solver::SolveResult res;
  res.n_states = n;
  res.sens_params = sens_params;
  std::vector<double> starts{0.0}, ends;
  for (double t : taus) {
    ends.push_back(t);
    starts.push_back(t);
  }
  ends.push_back(t_end);
  std::vector<double> fm(n), fp(n);
  for (size_t seg = 0; seg < starts.size(); ++seg) {
    const double t0 = starts[seg], t1 = ends[seg];
    std::vector<double> rel;
    for (double g : output_times)
      if ((seg == 0 ? g >= t0 : g > t0) && g <= t1) rel.push_back(g - t0);
    const bool endpoint_is_output = !rel.empty() && std::abs(rel.back() - (t1 - t0)) <= 1e-12 * std::max(1.0, t1);
    if (!endpoint_is_output) rel.push_back(t1 - t0);
    if (rel.size() == 1 && rel[0] == 0.0) rel.push_back(t1 - t0);  // degenerate first segment
    SegmentModel sm(model, y, t0, p, sens_params, S);
    solver::SolveResult r = solver::Simulator(sm, options).run(p, rel, roots, sens_params);
    const size_t last = r.t.size() - 1;
    for (size_t k = 0; k < r.t.size(); ++k) {
      if (k == last && !endpoint_is_output) break;
      if (seg > 0 && r.t[k] == 0.0) continue;
      res.t.push_back(t0 + r.t[k]);
      for (size_t i = 0; i < n; ++i) res.y.push_back(r.state(k, i));
      for (size_t i = 0; i < n; ++i)
        for (size_t c = 0; c < ns; ++c) res.s.push_back(r.sens(k, i, c) + S(i, c));
    }
    for (auto& e : r.events) {
      e.t += t0;
      for (size_t i = 0; i < n; ++i)
        for (size_t c = 0; c < ns; ++c) e.s[i * ns + c] += S(i, c);
      res.events.push_back(std::move(e));
    }
    res.stats.steps += r.stats.steps;
    res.stats.rhs_evals += r.stats.rhs_evals;
    res.stats.jac_evals += r.stats.jac_evals;
    res.stats.sens_rhs_evals += r.stats.sens_rhs_evals;
    res.stats.wall_seconds += r.stats.wall_seconds;
    // State and sensitivities at the end of the segment.
    for (size_t i = 0; i < n; ++i) y[i] = r.state(last, i);
    Eigen::MatrixXd S_end(n, ns);
    for (size_t i = 0; i < n; ++i)
      for (size_t c = 0; c < ns; ++c) S_end(i, c) = r.sens(last, i, c) + S(i, c);
    if (seg + 1 < starts.size()) {
      // Jump at the switch: s+ = s- + (f- - f+) dtau/dp.
      const double eps = 1e-9 * std::max(1.0, std::abs(t1));
      model.rhs(t1 - eps, y.data(), p.data(), fm.data());
      model.rhs(t1 + eps, y.data(), p.data(), fp.data());
      for (size_t i = 0; i < n; ++i)
        for (size_t c = 0; c < ns; ++c) S_end(i, c) += (fm[i] - fp[i]) * dtau(seg, c);
      ++res.stats.restarts;
    }
    S = S_end;
  }
  return res;
}

}  // namespace phasmid::sensitivity
