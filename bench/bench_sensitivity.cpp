// Cost of forward sensitivities: (time with sensitivities) / (plain simulation) for
// Np = 1, 4, 16 parameters, staggered vs simultaneous corrector, against finite differences
// (1 + Np one-sided runs, 1 + 2 Np central runs) measured in the same run.
//   build-sens/bench/bench_sensitivity [t_end_ms]
// Two models: the Section 3.1 mechanical FTi joint (2 states, 18 parameters) and a chain of
// 13 van der Pol oscillators (26 states like the single-joint network, 16 parameters).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <numeric>

#include "features/features.hpp"
#include "model/mechanical_joint_model.hpp"
#include "solver/simulator.hpp"

using namespace phasmid;

namespace {

// x_i'' = mu_i (1 - x_i^2) x_i' - w^2 x_i + k (x_{i-1} - 2 x_i + x_{i+1}) + a cos(w t), in ms.
class VdpChain : public model::OdeModelT<VdpChain> {
 public:
  explicit VdpChain(size_t n) : n_(n) {
    for (size_t i = 0; i < n; ++i)
      mu_.push_back(params_.add({"vdp.mu" + std::to_string(i), 0.02 + 0.001 * i, "1/ms", "bench", "damping"}));
    w_ = params_.add({"vdp.omega", 2 * M_PI / 500.0, "rad/ms", "bench", "angular frequency"});
    k_ = params_.add({"vdp.k", 1e-5, "1/ms^2", "bench", "coupling"});
    a_ = params_.add({"vdp.a", 1e-5, "1/ms^2", "bench", "forcing"});
    for (size_t i = 0; i < n; ++i) {
      add_state("vdp.x" + std::to_string(i), "1");
      add_state("vdp.v" + std::to_string(i), "1/ms");
    }
    angles_.push_back({"middle", "fti", 0, 1});
  }
  std::string kind() const override { return "vdp_chain"; }
  std::vector<double> initial_state(const std::vector<double>&) const override {
    std::vector<double> y(2 * n_, 0.0);
    for (size_t i = 0; i < n_; ++i) y[2 * i] = 1.0 + 0.1 * i;
    return y;
  }
  template <class T>
  void eval(double t, const T* y, const T* p, T* ydot) const {
    const T& w = p[w_];
    for (size_t i = 0; i < n_; ++i) {
      const T& x = y[2 * i];
      const T& v = y[2 * i + 1];
      T left = i > 0 ? y[2 * i - 2] : x, right = i + 1 < n_ ? y[2 * i + 2] : x;
      ydot[2 * i] = v;
      ydot[2 * i + 1] = p[mu_[i]] * (1.0 - x * x) * v - w * w * x + p[k_] * (left - 2.0 * x + right) +
                        p[a_] * std::cos(0.002 * t);
    }
  }

 private:
  size_t n_;
  std::vector<size_t> mu_;
  size_t w_, k_, a_;
};

double seconds(const std::function<void()>& f, int repeats) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

void bench(const char* label, const model::OdeModel& m, double t_end, int repeats) {
  auto p = m.parameters().values();
  const auto grid = solver::output_grid(t_end, 1.0);
  const auto roots = features::feature_roots(m);
  solver::SolverOptions stag, simul, noerr;
  simul.sensitivity_method = solver::SensitivityMethod::Simultaneous;
  noerr.sensitivity_error_control = false;
  solver::Simulator sim_stag(m, stag), sim_simul(m, simul), sim_noerr(m, noerr);
  solver::SolveResult r0;
  const double plain = seconds([&] { r0 = sim_stag.run(p, grid, roots); }, repeats);
  std::printf("\n%s: %zu states, %zu parameters, %.0f ms simulated, plain run %.4f s (best of %d), %ld steps\n",
              label, m.num_states(), p.size(), t_end, plain, repeats, r0.stats.steps);
  std::printf("%4s  %10s  %10s  %10s  %8s  %8s  %10s  %10s  %10s\n", "Np", "staggered", "simultan.", "no-errcon",
              "1+0.3Np", "1+0.5Np", "FD 1+Np", "FD 1+2Np", "steps x");
  for (size_t np : {1u, 4u, 16u}) {
    std::vector<size_t> idx(std::min(np, p.size()));
    std::iota(idx.begin(), idx.end(), 0);
    solver::SolveResult rs;
    const double ts = seconds([&] { rs = sim_stag.run(p, grid, roots, idx); }, repeats);
    const double tm = seconds([&] { sim_simul.run(p, grid, roots, idx); }, repeats);
    const double tn = seconds([&] { sim_noerr.run(p, grid, roots, idx); }, repeats);
    // Finite differences: nominal + one (one-sided) or two (central) runs per parameter.
    const double fd1 = seconds(
        [&] {
          sim_stag.run(p, grid, roots);
          for (size_t j : idx) {
            auto q = p;
            q[j] *= 1 + 1e-4;
            sim_stag.run(q, grid, roots);
          }
        },
        1);
    const double fd2 = seconds(
        [&] {
          sim_stag.run(p, grid, roots);
          for (size_t j : idx)
            for (double s : {1.0, -1.0}) {
              auto q = p;
              q[j] *= 1 + s * 1e-4;
              sim_stag.run(q, grid, roots);
            }
        },
        1);
    std::printf("%4zu  %10.2f  %10.2f  %10.2f  %8.1f  %8.1f  %10.2f  %10.2f  %10.2f\n", idx.size(), ts / plain,
                tm / plain, tn / plain, 1 + 0.3 * idx.size(), 1 + 0.5 * idx.size(), fd1 / plain, fd2 / plain,
                double(rs.stats.steps) / r0.stats.steps);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const double t_end = argc > 1 ? std::atof(argv[1]) : 9000.0;
  std::printf("bench_sensitivity: cost of forward sensitivities relative to a plain run (same roots, rtol = atol = 1e-8)\n");
  model::MechanicalJointModel fti("middle", model::JointType::Fti, true, 250, 500, 45);
  bench("mechanical FTi joint (Section 3.1)", fti, t_end, 5);
  VdpChain chain(13);
  bench("van der Pol chain (26 states)", chain, t_end, 3);
  std::printf("\nColumns: run time / plain run time; 'steps x' = CVODES steps with staggered sensitivities / plain steps.\n");
  return 0;
}
