// Prototype for lever 3 of issue #21 (bench/results "An exponential Runge-Kutta method,
// prototyped"): how many steps would an explicit method take on a whole walking network if the
// stiff diagonal of its Jacobian (the gates' alpha + beta, the potentials' g_tot / C) were
// integrated exactly? Not a solver of phasmid: no dense output, no events, a plain step
// controller, the diagonal by forward differences. Each method runs in this file with the same
// controller, so their step counts compare; accuracy is the largest difference of the FTi angle
// from a Dormand-Prince 1e-11 run (ARKODE) at checkpoints every 500 ms over 9 s. Usage:
//   bench_exprk [joint|leg|three] [TOLS=1e-4,1e-5,1e-6] [methods=dp5,lawson,rk4d,exprk4d]
//   (also exprk4e3, exprk4e2: embedded estimates, below)
// dp5: Dormand-Prince 5(4), embedded estimate. lawson: the same applied to
// v = exp(-(t - t_n) L) y, L the Jacobian's negative diagonal frozen at the step's start.
// rk4d / exprk4d: Hochbruck and Ostermann's five-stage exponential Runge-Kutta method of stiff
// order 4 (Acta Numerica 2010, the method "exprk4s5"), with L = 0 / that diagonal, the error by
// step doubling (three steps' work per step: compare steps, not evaluations).
// exprk4e3 / exprk4e2: the same method with an embedded estimate instead: the weights with stage
// 5 replaced by stage 3 (or 2), which share its node c = 1/2 and so satisfy the same quadrature
// conditions, give a third- (second-) order solution; their difference h (4 phi_2 - 8 phi_3)
// (N_5 - N_3) is the estimate, controlled with the exponent 1/4 (1/3). One step's work per step.
// BENCH_L_UNITS="mV" (comma-separated units) keeps only those states' diagonal in L: "mV", the
// membrane potentials alone, is the setting whose error follows the tolerance (bench/results).
#include <sundials/sundials_context.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "solver/dormand_prince_table.hpp"
#include "solver/erk_session.hpp"
#include "walking_models.hpp"

using namespace phasmid;

namespace {

constexpr double kCheckEvery = 500.0, kEnd = 9000.0;

struct Problem {
  const model::NetworkModel& m;
  std::vector<double> p;
  size_t n, angle;
  std::vector<double> stops;  // breakpoints and checkpoints, ascending
  std::vector<std::string> units;  // the units of the states in L (empty: all)
  long evals = 0;
  void f(double t, const double* y, double* out) {
    m.rhs(t, y, p.data(), out);
    ++evals;
  }
};

// phi_k(z) = sum_j z^j / (j + k)!, k = 1..3: the exponential methods' weights for diagonal L.
double phi(int k, double z) {
  if (std::fabs(z) < 1e-3) {
    double fact = 1.0;
    for (int i = 2; i <= k; ++i) fact *= i;
    double s = 0.0, term = 1.0 / fact;
    for (int j = 0; j < 8; ++j, term *= z / (j + k)) s += term;
    return s;
  }
  const double e = std::exp(z);
  if (k == 1) return (e - 1) / z;
  if (k == 2) return (e - 1 - z) / (z * z);
  return (e - 1 - z - 0.5 * z * z) / (z * z * z);
}

// The Jacobian's diagonal at (t, y), negative entries only (the relaxations), by differences;
// yp and fp are scratch.
void stiff_diagonal(Problem& P, double t, const std::vector<double>& y, const std::vector<double>& fy,
                    std::vector<double>& lam, std::vector<double>& yp, std::vector<double>& fp) {
  yp = y;
  for (size_t i = 0; i < P.n; ++i) {
    const double d = 1e-7 * std::max(1.0, std::fabs(y[i]));
    yp[i] = y[i] + d;
    P.f(t, yp.data(), fp.data());
    yp[i] = y[i];
    const double J = (fp[i] - fy[i]) / d;
    const bool chosen = P.units.empty() || std::find(P.units.begin(), P.units.end(), P.m.states()[i].unit) != P.units.end();
    lam[i] = J < 0 && chosen ? J : 0.0;
  }
}

// A method's stage buffers, sized once: every entry a step reads, it writes first.
void size_stages(int stages, size_t n, std::vector<std::vector<double>>& N, std::vector<std::vector<double>>& Y,
                 std::vector<double>& fy) {
  if (!N.empty()) return;
  N.assign(static_cast<size_t>(stages), std::vector<double>(n));
  Y = N;
  fy.resize(n);
}

// Dormand-Prince on v = exp(-(t - t_n) L) y (L = 0: Dormand-Prince itself). Writes y(t + h),
// returns the weighted RMS of the embedded error estimate.
struct LawsonDp5 {
  static constexpr const double (&c)[7] = solver::dormand_prince::kC;
  static constexpr const double (&A)[7][6] = solver::dormand_prince::kA;
  static constexpr const double (&bhat)[7] = solver::dormand_prince::kBhat;
  std::vector<std::vector<double>> N, Y;
  std::vector<double> fy;

  double step(Problem& P, double t, const std::vector<double>& y, const std::vector<double>& f0,
              const std::vector<double>& lam, double h, double tol, std::vector<double>& out) {
    size_stages(7, P.n, N, Y, fy);
    for (size_t k = 0; k < P.n; ++k) N[0][k] = f0[k] - lam[k] * y[k];
    for (int i = 1; i < 7; ++i) {
      for (size_t k = 0; k < P.n; ++k) {
        double s = 0;
        for (int j = 0; j < i; ++j) s += A[i][j] * std::exp((c[i] - c[j]) * h * lam[k]) * N[j][k];
        Y[i][k] = std::exp(c[i] * h * lam[k]) * y[k] + h * s;
      }
      P.f(t + c[i] * h, Y[i].data(), fy.data());
      for (size_t k = 0; k < P.n; ++k) N[i][k] = fy[k] - lam[k] * Y[i][k];
    }
    double en = 0;
    for (size_t k = 0; k < P.n; ++k) {
      double e = 0;
      for (int j = 0; j < 7; ++j) e += ((j < 6 ? A[6][j] : 0.0) - bhat[j]) * std::exp((1 - c[j]) * h * lam[k]) * N[j][k];
      const double w = tol * (1.0 + std::max(std::fabs(y[k]), std::fabs(Y[6][k])));
      en += (h * e / w) * (h * e / w);
    }
    out = Y[6];
    return std::sqrt(en / P.n);
  }
};

// One step of exprk4s5 with diagonal L (L = 0: a classical fourth-order method).
struct ExpRk4 {
  std::vector<std::vector<double>> N, U;
  std::vector<double> fy;

  void step(Problem& P, double t, const std::vector<double>& y, const std::vector<double>& f0,
            const std::vector<double>& lam, double h, std::vector<double>& out, int embed = 0,
            std::vector<double>* err = nullptr) {
    const double c[5] = {0, 0.5, 0.5, 1, 0.5};
    size_stages(5, P.n, N, U, fy);
    for (size_t k = 0; k < P.n; ++k) N[0][k] = f0[k] - lam[k] * y[k];
    for (int i = 1; i < 5; ++i) {
      for (size_t k = 0; k < P.n; ++k) U[i][k] = std::exp(c[i] * h * lam[k]) * y[k] + h * stage_sum(i, h * lam[k], k);
      P.f(t + c[i] * h, U[i].data(), fy.data());
      for (size_t k = 0; k < P.n; ++k) N[i][k] = fy[k] - lam[k] * U[i][k];
    }
    out.resize(P.n);
    for (size_t k = 0; k < P.n; ++k) {
      const double z = h * lam[k], p1 = phi(1, z), p2 = phi(2, z), p3 = phi(3, z);
      out[k] = std::exp(z) * y[k] +
               h * ((p1 - 3 * p2 + 4 * p3) * N[0][k] + (-p2 + 4 * p3) * N[3][k] + (4 * p2 - 8 * p3) * N[4][k]);
      if (err) (*err)[k] = h * (4 * p2 - 8 * p3) * (N[4][k] - N[embed][k]);
    }
  }

  // sum_j a_ij(hL) N_j for state k, z = h lambda_k (phi_{l,i} = phi_l(c_i z)).
  double stage_sum(int i, double z, size_t k) const {
    const double p1 = phi(1, i == 3 ? z : 0.5 * z), p2 = phi(2, i == 3 ? z : 0.5 * z);
    if (i == 1) return 0.5 * p1 * N[0][k];
    if (i == 2) return (0.5 * p1 - p2) * N[0][k] + p2 * N[1][k];
    if (i == 3) return (p1 - 2 * p2) * N[0][k] + p2 * (N[1][k] + N[2][k]);
    const double p24 = phi(2, z), p34 = phi(3, z), p35 = phi(3, 0.5 * z);
    const double a52 = 0.5 * p2 - p34 + 0.25 * p24 - 0.5 * p35, a54 = 0.25 * p2 - a52;
    return (0.5 * p1 - 2 * a52 - a54) * N[0][k] + a52 * (N[1][k] + N[2][k]) + a54 * N[3][k];
  }
};

struct Outcome {
  long steps = 0, rejects = 0, evals = 0;
  std::vector<double> angles;  // at the checkpoints
};

// The whole run with one method and tolerance: its steps, rejected steps, evaluations and the
// angle at each checkpoint. A step is accepted when its error norm is <= 1.
Outcome run(Problem& P, const std::string& method, double tol) {
  const bool expo = method == "lawson" || method == "exprk4d" || method == "exprk4e3" || method == "exprk4e2";
  const int embed = method == "exprk4e3" || method == "rk4e3" ? 2 : method == "exprk4e2" || method == "rk4e2" ? 1 : 0;
  const double expo_err = embed == 2 ? 0.25 : embed == 1 ? 1.0 / 3 : 0.2;
  std::vector<double> est(P.n);
  LawsonDp5 dp5;
  ExpRk4 rk4;
  std::vector<double> y = P.m.initial_state(P.p), f0(P.n), lam(P.n, 0.0), y1(P.n), ym(P.n), fm(P.n), y2(P.n),
                      yp(P.n), fp(P.n);
  Outcome o;
  P.evals = 0;
  double t = 0, h = 0.01;
  for (double stop : P.stops) {
    while (t < stop) {
      P.f(t, y.data(), f0.data());
      if (expo) stiff_diagonal(P, t, y, f0, lam, yp, fp);
      for (;;) {
        const bool last = t + h >= stop;
        const double hs = last ? stop - t : h;
        double en;
        if (method == "dp5" || method == "lawson") {
          en = dp5.step(P, t, y, f0, lam, hs, tol, y2);
        } else if (embed) {
          rk4.step(P, t, y, f0, lam, hs, y2, embed, &est);
          en = 0;
          for (size_t k = 0; k < P.n; ++k) {
            const double e = est[k] / (tol * (1.0 + std::max(std::fabs(y[k]), std::fabs(y2[k]))));
            en += e * e;
          }
          en = std::sqrt(en / P.n);
        } else {  // step doubling: the error of the two half steps is (y2 - y1) / 15
          rk4.step(P, t, y, f0, lam, hs, y1);
          rk4.step(P, t, y, f0, lam, 0.5 * hs, ym);
          P.f(t + 0.5 * hs, ym.data(), fm.data());
          rk4.step(P, t + 0.5 * hs, ym, fm, lam, 0.5 * hs, y2);
          en = 0;
          for (size_t k = 0; k < P.n; ++k) {
            const double e = (y2[k] - y1[k]) / 15.0 / (tol * (1.0 + std::max(std::fabs(y[k]), std::fabs(y2[k]))));
            en += e * e;
          }
          en = std::sqrt(en / P.n);
        }
        if (!(en <= 1.0)) {  // a non-finite estimate (a state overflowed in a too long step) too
          ++o.rejects;
          h = hs * (en > 1.0 ? std::max(0.2, 0.9 * std::pow(en, -expo_err)) : 0.2);
          continue;
        }
        const double grow = 0.9 * std::pow(std::max(en, 1e-10), -expo_err);
        t = last ? stop : t + hs;
        y = y2;
        ++o.steps;
        h = hs * std::min(5.0, std::max(0.2, grow));
        break;
      }
    }
    if (std::fmod(stop, kCheckEvery) == 0.0) o.angles.push_back(y[P.angle]);
  }
  o.evals = P.evals;
  return o;
}

int rhs_cb(double t, N_Vector y, N_Vector ydot, void* ud) {
  auto* P = static_cast<Problem*>(ud);
  P->m.rhs(t, N_VGetArrayPointer(y), P->p.data(), N_VGetArrayPointer(ydot));
  return 0;
}

// The FTi angle at the checkpoints from ARKODE's Dormand-Prince at rtol = atol = 1e-11.
std::vector<double> reference(Problem& P) {
  SUNContext ctx;
  SUNContext_Create(nullptr, &ctx);
  solver::SolverOptions o;
  o.rtol = o.atol = 1e-11;
  o.integrator = solver::IntegratorKind::ErkDp5;
  const std::vector<double> y0 = P.m.initial_state(P.p);
  std::vector<double> out;
  {
    solver::ErkSession s(ctx, o, y0.data(), y0.size(), rhs_cb, &P);
    s.set_stop_time(kEnd);
    for (double tc = kCheckEvery; tc <= kEnd; tc += kCheckEvery) {
      double tr = 0;
      if (s.advance(tc, &tr, 1) < 0) break;
      out.push_back(NV_Ith_S(s.y(), P.angle));
    }
  }
  SUNContext_Free(&ctx);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string which = argc > 1 ? argv[1] : "joint";
  const auto tols = bench::split_list(argc > 2 ? argv[2] : "1e-4,1e-5,1e-6");
  const auto methods = bench::split_list(argc > 3 ? argv[3] : "dp5,lawson,rk4d,exprk4d");
  std::unique_ptr<model::NetworkModel> m = bench::build_walking_model(which, model::MotoneuronModel::Spiking);
  Problem P{*m, m->parameters().values(), m->num_states(), m->joints().back().angle_state, {}};
  P.stops = m->breakpoints(P.p, kEnd);
  for (double t = kCheckEvery; t <= kEnd; t += kCheckEvery) P.stops.push_back(t);
  std::sort(P.stops.begin(), P.stops.end());
  P.stops.erase(std::unique(P.stops.begin(), P.stops.end()), P.stops.end());
  if (const char* u = std::getenv("BENCH_L_UNITS")) P.units = bench::split_list(u);
  const std::vector<double> ref = reference(P);
  std::printf("| method | tol | steps | rejected | evaluations | max angle err deg (checkpoints) |\n|---|---:|---:|---:|---:|---:|\n");
  for (const auto& method : methods)
    for (const auto& ts : tols) {
      const Outcome o = run(P, method, std::atof(ts.c_str()));
      double err = 0;
      for (size_t i = 0; i < std::min(ref.size(), o.angles.size()); ++i) err = std::max(err, std::fabs(o.angles[i] - ref[i]));
      std::printf("| %s | %s | %ld | %ld | %ld | %.5f |\n", method.c_str(), ts.c_str(), o.steps, o.rejects, o.evals,
                  err * 180.0 / M_PI);
      std::fflush(stdout);
    }
  return 0;
}
