// IMEX (ARKStep, implicit part -kappa(y) y: solver/ark_imex_session.hpp) against ERKStep
// Dormand-Prince on a network model, without events: the FTi angle is sampled every 0.05 ms
// over 9 s, its maxima located by parabolas, and the period and mean extremal angles over
// 2000-9000 ms compared with Dormand-Prince at rtol = atol = 1e-11. Usage:
//   bench_imex [joint|leg|three] [spiking|rate] [TOLS=1e-4,1e-5,1e-6] [methods=dp5,ark4,ark5,ark4v,ark5v]
// ark4v/ark5v: only the membrane potentials implicit; a further "l" (ark4l, ark4vl): one
// Newton iteration per stage (ImexOptions::linearly_implicit). CPU seconds, best of BENCH_REPEATS (3).
#include <sundials/sundials_context.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "model/stiff_rates.hpp"
#include "solver/ark_imex_session.hpp"
#include "solver/erk_session.hpp"
#include "walking_models.hpp"

using namespace phasmid;

namespace {

struct Data {
  const model::NetworkModel* m;
  std::vector<double> p;
};

int rhs(double t, N_Vector y, N_Vector ydot, void* ud) {
  auto* d = static_cast<Data*>(ud);
  d->m->rhs(t, N_VGetArrayPointer(y), d->p.data(), N_VGetArrayPointer(ydot));
  return 0;
}

struct Features {
  double period = NAN, max_deg = NAN, min_deg = NAN;
  long steps = 0, rhs = 0, newton = 0;
  double cpu = 0.0;
};

// Mean of the parabola-interpolated extrema of a sampled angle (sign +1 maxima, -1 minima).
void extrema(const std::vector<double>& a, double dt, double t0, int sign, std::vector<double>& t, std::vector<double>& v) {
  for (size_t i = 1; i + 1 < a.size(); ++i) {
    if (sign * (a[i] - a[i - 1]) > 0 && sign * (a[i] - a[i + 1]) >= 0) {
      const double den = a[i - 1] - 2 * a[i] + a[i + 1];
      const double off = den != 0 ? 0.5 * (a[i - 1] - a[i + 1]) / den : 0.0;
      const double ti = t0 + (i + off) * dt;
      if (ti < 2000.0) continue;
      t.push_back(ti);
      v.push_back(a[i] - 0.25 * (a[i - 1] - a[i + 1]) * off);
    }
  }
}

Features run(const model::NetworkModel& m, const std::string& method, double tol) {
  SUNContext ctx;
  SUNContext_Create(nullptr, &ctx);
  Data d{&m, m.parameters().values()};
  const std::vector<double> y0 = m.initial_state(d.p);
  solver::SolverOptions o;
  o.rtol = o.atol = tol;
  o.integrator = solver::IntegratorKind::ErkDp5;
  std::unique_ptr<solver::IntegratorSession> s;
  if (method == "dp5") {
    s = std::make_unique<solver::ErkSession>(ctx, o, y0.data(), y0.size(), rhs, &d);
  } else {
    model::StiffRateOptions so;
    so.gates = method.find('v') == std::string::npos;
    solver::ImexOptions imex;
    imex.order = method[3] - '0';
    imex.linearly_implicit = method.find('l') != std::string::npos;
    auto kappa = [&m, &d, so](double, const double* y, double* k) { model::stiff_rates(m, y, d.p.data(), k, so); };
    s = std::make_unique<solver::ArkImexSession>(ctx, o, y0.data(), y0.size(), rhs, &d, kappa,
                                                   model::stiff_offsets(m, d.p.data()), imex);
  }
  const double dt = 0.05, t_end = 9000.0;
  const size_t angle = m.joints().back().angle_state;
  std::vector<double> a;
  std::clock_t c0 = std::clock();
  s->set_stop_time(t_end);
  for (int i = 1; i * dt <= t_end + 1e-9; ++i) {
    double t = 0;
    const int flag = s->advance(i * dt, &t, 1);
    if (flag < 0) {
      std::fprintf(stderr, "%s %g: %s at t = %g\n", method.c_str(), tol, s->flag_name(flag).c_str(), t);
      break;
    }
    a.push_back(NV_Ith_S(s->y(), angle) * 180.0 / M_PI);
  }
  Features f;
  f.cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
  const auto st = s->stats();
  f.steps = st.steps;
  f.rhs = st.rhs_evals;
  f.newton = st.newton_iterations;
  if (std::getenv("BENCH_VERBOSE"))
    std::fprintf(stderr, "# %s %g: error-test failures %ld, Newton failures %ld, set-ups %ld\n", method.c_str(), tol,
                 st.error_test_failures, st.newton_failures, st.linear_setups);
  std::vector<double> tmax, vmax, tmin, vmin;
  extrema(a, dt, dt, +1, tmax, vmax);
  extrema(a, dt, dt, -1, tmin, vmin);
  if (tmax.size() > 1) f.period = (tmax.back() - tmax.front()) / (tmax.size() - 1);
  double sx = 0, sn = 0;
  for (double v : vmax) sx += v;
  for (double v : vmin) sn += v;
  f.max_deg = sx / vmax.size();
  f.min_deg = sn / vmin.size();
  s.reset();
  SUNContext_Free(&ctx);
  return f;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string which = argc > 1 ? argv[1] : "joint";
  const model::MotoneuronModel mn = model::parse_motoneuron_model(argc > 2 ? argv[2] : "spiking");
  const auto tols = bench::split_list(argc > 3 ? argv[3] : "1e-4,1e-5,1e-6");
  const auto methods = bench::split_list(argc > 4 ? argv[4] : "dp5,ark4,ark5,ark4v,ark5v");
  const int repeats = std::getenv("BENCH_REPEATS") ? std::max(1, std::atoi(std::getenv("BENCH_REPEATS"))) : 3;
  std::unique_ptr<model::NetworkModel> m = bench::build_walking_model(which, mn);
  const Features ref = run(*m, "dp5", 1e-11);
  std::printf("# bench_imex %s %s: reference DP5 1e-11: period %.6f ms, angles %.6f / %.6f deg, %ld steps\n",
              which.c_str(), argc > 2 ? argv[2] : "spiking", ref.period, ref.min_deg, ref.max_deg, ref.steps);
  std::printf("| method | rtol = atol | CPU s | steps | f_E evals | Newton its | period err ms | max err deg | min err deg |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& method : methods)
    for (const auto& ts : tols) {
      Features best;
      best.cpu = 1e300;
      for (int r = 0; r < repeats; ++r) {
        Features f = run(*m, method, std::atof(ts.c_str()));
        if (f.cpu < best.cpu) best = f;
      }
      std::printf("| %s | %s | %.3f | %ld | %ld | %ld | %+.5f | %+.5f | %+.5f |\n", method.c_str(), ts.c_str(), best.cpu,
                  best.steps, best.rhs, best.newton, best.period - ref.period, best.max_deg - ref.max_deg,
                  best.min_deg - ref.min_deg);
      std::fflush(stdout);
    }
  return 0;
}
