// Cost of forward sensitivities: (time with sensitivities) / (plain simulation) for
// Np = 1, 4, 16 parameters and several ways of running them (variants()), against one-sided
// finite differences (1 + Np runs) measured in the same run; then the accuracy of each
// variant's feature sensitivities for the network.
//   build/bench/bench_sensitivity [t_end_ms [t_network_ms [mech,vdp,net,accuracy,rate,rate-accuracy,leg [variant,...]]]]
// Models: the Section 3.1 mechanical FTi joint (2 states, 18 parameters), a chain of
// 13 van der Pol oscillators (26 states, 16 parameters), the single-joint FTi network
// (configs/single_joint_fti.toml, 26 states, spiking motoneurons; default 2500 ms; `rate`:
// the same with rate motoneurons, 20 states) and the middle leg (`leg`:
// configs/middle_leg_forward.toml, 78 states, t_network_ms / 5 simulated).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <functional>
#include <numeric>
#include <string>

#include "config/config.hpp"
#include "features/features.hpp"
#include "model/mechanical_joint_model.hpp"
#include "sensitivity/sensitivity.hpp"
#include "solver/simulator.hpp"
#include "build_info.hpp"

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

// CPU seconds of this (single-threaded) process: on a shared, loaded machine the wall clock
// mostly measures the other jobs.
double cpu_now() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

double seconds(const std::function<void()>& f, int repeats) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const double t0 = cpu_now();
    f();
    best = std::min(best, cpu_now() - t0);
  }
  return best;
}

std::string g_only;  // comma-separated variant labels to run (empty: all)

// One way of running the sensitivities (columns of the table).
struct Variant {
  const char* label;
  solver::SolverOptions options;
};

std::vector<Variant> variants() {
  solver::SolverOptions o;  // the defaults: simultaneous corrector, batched Jet<8> right-hand side, errcon, EE tolerances
  o.sensitivities_at_outputs = false;  // as analyse_sensitivities without trajectory output
  std::vector<Variant> v{{"default", o}};
  auto add = [&](const char* label, const std::function<void(solver::SolverOptions&)>& change) {
    solver::SolverOptions x = o;
    change(x);
    v.push_back({label, x});
  };
  add("stagg.", [](auto& x) { x.sensitivity_method = solver::SensitivityMethod::Staggered; });
  add("tolS x10", [](auto& x) { x.sensitivity_tolerance_factor = 10.0; });
  add("tolS x100", [](auto& x) { x.sensitivity_tolerance_factor = 100.0; });
  add("tolS x1e3", [](auto& x) { x.sensitivity_tolerance_factor = 1000.0; });
  add("tolS x1e4", [](auto& x) { x.sensitivity_tolerance_factor = 1e4; });
  add("no-errcon", [](auto& x) { x.sensitivity_error_control = false; });
  add("stg-noerr", [](auto& x) {
    x.sensitivity_error_control = false;
    x.sensitivity_method = solver::SensitivityMethod::Staggered;
  });
  add("klu", [](auto& x) { x.linear_solver = solver::LinearSolverKind::Klu; });
  add("dense", [](auto& x) { x.linear_solver = solver::LinearSolverKind::Dense; });
  add("+traj", [](auto& x) { x.sensitivities_at_outputs = true; });
  if (!g_only.empty()) {  // keep the default (the reference for 'steps x') and the chosen ones
    std::vector<Variant> kept{v[0]};
    for (size_t k = 1; k < v.size(); ++k)
      if (("," + g_only + ",").find("," + std::string(v[k].label) + ",") != std::string::npos) kept.push_back(v[k]);
    v = kept;
  }
  return v;
}

// Parameters for Np sensitivities: the first Np, or `names` (a model's meaningful ones) first.
std::vector<size_t> pick(const model::OdeModel& m, size_t np, const std::vector<std::string>& names) {
  std::vector<size_t> idx;
  for (auto& n : names)
    if (idx.size() < np) idx.push_back(m.parameters().index(n));
  const auto p = m.parameters().values();
  for (size_t k = 0; k < p.size() && idx.size() < np; ++k)
    if (std::find(idx.begin(), idx.end(), k) == idx.end() && p[k] != 0.0) idx.push_back(k);
  return idx;
}

void bench(const char* label, const model::OdeModel& m, double t_end, int repeats,
           const std::vector<std::string>& names = {}) {
  auto p = m.parameters().values();
  const auto grid = solver::output_grid(t_end, 1.0);
  const auto roots = features::feature_roots(m);
  auto vs = variants();
  solver::Simulator plain_sim(m, vs[0].options);
  solver::SolveResult r0;
  auto plain_run = [&] { r0 = plain_sim.run(p, grid, roots); };
  const int reps = std::max(repeats, 3);
  const double plain = seconds(plain_run, reps);
  // Every ratio is the best of `reps` alternations of (plain run, measured run): on a shared
  // machine the speed of the same binary drifts within seconds, so a baseline measured once at
  // the start skews whole columns; adjacent pairs see the same machine state.
  auto ratio = [&](const std::function<void()>& run) {
    double best_plain = 1e300, best = 1e300;
    for (int r = 0; r < reps; ++r) {
      best_plain = std::min(best_plain, seconds(plain_run, 1));
      best = std::min(best, seconds(run, 1));
    }
    return best / best_plain;
  };
  std::printf("\n%s: %zu states, %zu parameters, %.0f ms simulated, plain run %.4f CPU s (best of %d), %ld steps\n",
              label, m.num_states(), p.size(), t_end, plain, reps, r0.stats.steps);
  std::printf("%4s", "Np");
  for (auto& v : vs) std::printf("  %9s", v.label);
  std::printf("  %7s  %7s  %9s  %9s\n", "1+0.3Np", "1+0.5Np", "FD 1+Np", "steps x");
  for (size_t np : {1u, 4u, 16u}) {
    std::vector<size_t> idx = pick(m, np, names);
    std::printf("%4zu", idx.size());
    long steps = 0;
    for (auto& v : vs) {
      solver::Simulator sim(m, v.options);
      solver::SolveResult rs;
      std::printf("  %9.2f", ratio([&] { rs = sim.run(p, grid, roots, idx); }));
      std::fflush(stdout);
      if (&v == &vs[0]) steps = rs.stats.steps;
    }
    // Finite differences: nominal + one (one-sided) run per parameter.
    const double fd1 = ratio([&] {
      plain_sim.run(p, grid, roots);
      for (size_t j : idx) {
        auto q = p;
        q[j] *= 1 + 1e-4;
        plain_sim.run(q, grid, roots);
      }
    });
    std::printf("  %7.1f  %7.1f  %9.2f  %9.2f\n", 1 + 0.3 * idx.size(), 1 + 0.5 * idx.size(), fd1,
                double(steps) / r0.stats.steps);
  }
}

// Accuracy of each variant: feature sensitivities against a reference (forward, errcon on,
// rtol = atol = 1e-10; tests/sensitivity/test_network_sensitivity.cpp checks that reference
// against central differences), as the largest relative deviation over the features whose
// relative sensitivity exceeds 0.01.
void accuracy(const char* label, const model::OdeModel& m, double t_end, double discard,
              const std::vector<std::string>& names) {
  auto p = m.parameters().values();
  sensitivity::SensitivityOptions o;
  o.parameters = names;
  o.t_end_ms = t_end;
  o.discard_ms = discard;
  o.write_trajectory = false;
  o.solver.rtol = o.solver.atol = 1e-10;
  auto ref = sensitivity::analyse_sensitivities(m, p, o);
  std::printf("\naccuracy, %s, Np = %zu, %.0f ms (features after %.0f ms): max |dF/dp - ref| / |ref| over %s\n", label,
              names.size(), t_end, discard, "features with |relative| > 0.01");
  std::printf("%10s  %9s  %9s  %s\n", "variant", "max dev", "CPU s", "worst feature / parameter");
  auto vs = variants();
  for (auto& v : vs) {
    o.solver = v.options;
    sensitivity::SensitivityReport r;
    const double cpu = seconds([&] { r = sensitivity::analyse_sensitivities(m, p, o); }, 1);
    double worst = 0;
    std::string where = "-";
    for (size_t f = 0; f < ref.features.size(); ++f)
      for (size_t j = 0; j < names.size(); ++j) {
        if (!(std::abs(ref.relative(f, j)) > 0.01)) continue;
        const size_t g = r.feature_index(ref.features[f].name);
        const double dev = std::abs(r.absolute(g, j) - ref.absolute(f, j)) / std::abs(ref.absolute(f, j));
        if (dev > worst) {
          worst = dev;
          where = ref.features[f].name + " / " + names[j];
        }
      }
    std::printf("%10s  %9.2e  %9.2f  %s\n", v.label, worst, cpu, where.c_str());
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const double t_end = argc > 1 ? std::atof(argv[1]) : 9000.0;
  const double t_net = argc > 2 ? std::atof(argv[2]) : 2500.0;
  const std::string parts = argc > 3 ? argv[3] : "mech,vdp,net,accuracy";
  g_only = argc > 4 ? argv[4] : "";
  auto want = [&](const char* part) { return ("," + parts + ",").find("," + std::string(part) + ",") != std::string::npos; };
  std::printf("bench_sensitivity: cost of forward sensitivities relative to a plain run (same roots, rtol = atol = 1e-8;\n"
              "CPU time of this process)\n");
  if (want("mech")) {
    model::MechanicalJointModel fti("middle", model::JointType::Fti, true, 250, 500, 45);
    bench("mechanical FTi joint (Section 3.1)", fti, t_end, 5);
  }
  if (want("vdp")) {
    VdpChain chain(13);
    bench("van der Pol chain (26 states)", chain, t_end, 3);
  }
  auto cfg = config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/single_joint_fti.toml");
  auto net = config::build_model(cfg);
  const std::vector<std::string> net_params = {"middle.fti.cpg_flx.g_app", "middle.fti.cpg_ext.g_app",
                                               "middle.fti.k_F.flexion", "middle.fti.k_E.extension"};
  if (want("net")) bench("single-joint FTi network (configs/single_joint_fti.toml)", *net, t_net, 1, net_params);
  if (want("accuracy")) accuracy("single-joint FTi network", *net, t_net, 1000.0, net_params);
  if (want("rate")) {  // the same network with non-spiking rate motoneurons (docs/model.md)
    std::string text = cfg.text;
    const size_t at = text.find("[model]");
    text.insert(at + 7, "\nmotoneuron = \"rate\"");
    auto rate = config::build_model(config::parse_config(text, cfg.path + " + motoneuron = \"rate\""));
    bench("single-joint FTi network, rate motoneurons (motoneuron = \"rate\")", *rate, t_net, 1, net_params);
    if (want("rate-accuracy")) accuracy("single-joint FTi network, rate motoneurons", *rate, t_net, 1000.0, net_params);
  }
  if (want("leg")) {  // a larger model: the middle leg's three joint networks, t_network_ms / 5
    auto leg = config::build_model(config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/middle_leg_forward.toml"));
    bench("middle leg (configs/middle_leg_forward.toml)", *leg, t_net / 5, 1, net_params);
  }
  std::printf("\nColumns: run time / plain run time (default = simultaneous corrector, batched Jet<8>/Jet<4> sensitivity right-hand\n"
              "side, sensitivity error control with EE tolerances, sensitivities fetched at events only); 'steps x' = CVODES\n"
              "steps of the default / plain steps.\n");
  return 0;
}
