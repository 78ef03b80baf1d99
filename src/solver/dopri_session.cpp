#include "solver/dopri_session.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "solver/dormand_prince_table.hpp"

namespace phasmid::solver {

namespace {

constexpr double kUround = std::numeric_limits<double>::epsilon();
// A failed stage's error norm: large enough that the controller takes its smallest step (0.1 h).
constexpr double kFailedNorm = 1e10;
constexpr int kMaxErrorFailures = 50;  // spike flanks reject several steps in a row (ARKODE's 7 is too few)

// ERKStep's default adaptivity (ERKStepSetDefaults and arkode_adapt_impl.h, SUNDIALS 6.4): a PI
// controller with exponents over the embedding's order 4, and the bounds named as there.
constexpr double kBias = 1.2, kSafety = 0.99, kGrowth = 25.0, kFirstGrowth = 1e4, kEtaMin = 0.1, kEtaMaxFail = 0.3;
constexpr double kK1 = -0.8 / 4, kK2 = 0.31 / 4, kTiny = 1e-10;
constexpr double kKeepLow = 1.0, kKeepHigh = 1.5;
constexpr int kSmallFailures = 2;

using dormand_prince::kA;
using dormand_prince::kC;
// The solution's weights (row 6 of A; the seventh is 0) minus the embedding's.
constexpr double kE[7] = {kA[6][0] - dormand_prince::kBhat[0], 0, kA[6][2] - dormand_prince::kBhat[2],
                          kA[6][3] - dormand_prince::kBhat[3], kA[6][4] - dormand_prince::kBhat[4],
                          kA[6][5] - dormand_prince::kBhat[5], -dormand_prince::kBhat[6]};

// Flags with CVODES' values (integrator_session.hpp).
constexpr int kTooMuchWork = -1, kErrFailure = -3, kRhsFail = -8, kIllInput = -22, kBadT = -25;

int sign_of(double g) { return g > 0 ? 1 : (g < 0 ? -1 : 0); }

}  // namespace

DopriSession::DopriSession(SUNContext ctx, const SolverOptions& options, const double* y0, size_t n, CVRhsFn rhs,
                           void* user_data)
    : rhs_(rhs),
      user_data_(user_data),
      n_(n),
      rtol_(options.rtol),
      atol_(n, options.atol),
      max_steps_(options.max_steps),
      hmax_(options.max_step_ms) {
  y_.reset(new_state_vector(ctx, y0, n));
  for (OwnedVector* v : {&yn_, &yold_, &ynew_, &stage_, &fold_}) v->reset(N_VClone(y_.get()));
  for (OwnedVector& k : k_) k.reset(N_VClone(y_.get()));
  for (OwnedVector& k : k_) N_VConst(0.0, k.get());  // read by dky before the first advance
  std::copy(y0, y0 + n, data(yn_));
}

void DopriSession::init_roots(const std::vector<int>& directions, CVRootFn g) {
  if (directions.empty()) return;
  root_ = g;
  dirs_ = directions;
  found_.assign(dirs_.size(), 0);
  last_sign_.assign(dirs_.size(), 0);
  glo_.resize(dirs_.size());
  ghi_.resize(dirs_.size());
  gmid_.resize(dirs_.size());
  started_ = false;  // the root signs are taken at the start
}

void DopriSession::set_stop_time(double t) {
  tstop_ = t;
  tstop_set_ = true;
}

void DopriSession::set_state_atol(const std::vector<double>& atol) { atol_ = atol; }

// The slope is taken here, not at the next advance, so that dky(t, 1) is right in between.
void DopriSession::restart(double t) {
  tn_ = told_ = t;
  h_last_ = 0.0;
  std::copy(data(y_), data(y_) + n_, data(yn_));
  ++stats_.rhs_evals;
  slope_current_ = rhs_(tn_, yn_.get(), k_[0].get(), user_data_) == 0;
  started_ = false;
}

int DopriSession::start(double tout) {
  if (!slope_current_) {
    ++stats_.rhs_evals;
    if (rhs_(tn_, yn_.get(), k_[0].get(), user_data_) != 0) return kRhsFail;
  }
  slope_current_ = false;
  told_ = tret_last_ = tn_;
  h_last_ = 0.0;
  h_ = initial_step(tout);
  ehist_ = 1.0;
  etamax_ = kFirstGrowth;
  if (root_) {
    eval_roots(tn_, glo_);
    for (size_t i = 0; i < glo_.size(); ++i) last_sign_[i] = sign_of(glo_[i]);  // 0: no sign until it leaves 0
    tlo_ = tn_;
  }
  started_ = true;
  return 0;
}

// ARKODE's first-step estimate (arkHin, SUNDIALS 6.4): between 100 ulp of the time and a
// tenth of the way to tout (or the stop), and no state moving by more than a tenth of its
// size plus its tolerance, half the step whose second-derivative estimate by an Euler step
// makes the local error 1 (up to four refinements).
double DopriSession::initial_step(double tout) {
  if (tstop_set_ && (tout - tn_) * (tout - tstop_) > 0) tout = tstop_;
  const double tdist = std::fabs(tout - tn_), tround = kUround * std::max(std::fabs(tn_), std::fabs(tout));
  if (tdist < 2 * tround) return std::max(tdist, kUround);
  const double *y = data(yn_), *f = data(k_[0]);
  double hub_inv = 0;
  for (size_t i = 0; i < n_; ++i)
    hub_inv = std::max(hub_inv, std::fabs(f[i]) / (0.1 * std::fabs(y[i]) + rtol_ * std::fabs(y[i]) + atol_[i]));
  const double hlb = 100 * tround;
  double hub = 0.1 * tdist;
  if (hub * hub_inv > 1) hub = 1 / hub_inv;
  double hg = std::sqrt(hlb * hub);
  if (hub < hlb) return hg;
  double hnew = hg;
  for (int round = 1; round <= 4; ++round) {
    double ydd = 0;
    bool ok = false;
    for (int tries = 0; tries < 4 && !ok; ++tries) {
      ok = second_derivative_norm(hg, &ydd);
      if (!ok) hg *= 0.2;
    }
    if (!ok) break;  // keep the last step whose slope was finite
    hnew = ydd * hub * hub > 2 ? std::sqrt(2 / ydd) : std::sqrt(hg * hub);
    if (round == 4) break;
    const double ratio = hnew / hg;
    if (ratio > 0.5 && ratio < 2) break;
    if (round > 1 && ratio > 2) {
      hnew = hg;
      break;
    }
    hg = hnew;
  }
  double h = std::min(std::max(0.5 * hnew, hlb), hub);
  if (hmax_ > 0) h = std::min(h, hmax_);
  return h;
}

// The weighted RMS norm of (f(tn + h, yn + h fn) - fn) / h; false if that slope failed.
bool DopriSession::second_derivative_norm(double h, double* norm) {
  const double *y = data(yn_), *f = data(k_[0]);
  double* u = data(stage_);
  for (size_t i = 0; i < n_; ++i) u[i] = y[i] + h * f[i];
  ++stats_.rhs_evals;
  if (rhs_(tn_ + h, stage_.get(), k_[1].get(), user_data_) != 0) return false;
  const double* f1 = data(k_[1]);
  double sum = 0;
  for (size_t i = 0; i < n_; ++i) {
    const double r = (f1[i] - f[i]) / h / (rtol_ * std::fabs(y[i]) + atol_[i]);
    sum += r * r;
  }
  *norm = std::sqrt(sum / static_cast<double>(n_));
  return std::isfinite(*norm);
}

namespace {

// Stage S's input u = y + h sum_j a_Sj k_j, unrolled over j so that the loop over the states
// vectorises (the stages are distinct arrays).
template <int S>
void stage_input(size_t n, double h, const double* __restrict y, const double* const* k, double* __restrict u) {
  const double* __restrict k0 = k[0];
  for (size_t i = 0; i < n; ++i) {
    double acc = kA[S][0] * k0[i];
    if constexpr (S > 1) acc += kA[S][1] * k[1][i];
    if constexpr (S > 2) acc += kA[S][2] * k[2][i];
    if constexpr (S > 3) acc += kA[S][3] * k[3][i];
    if constexpr (S > 4) acc += kA[S][4] * k[4][i];
    if constexpr (S > 5) acc += kA[S][5] * k[5][i];
    u[i] = y[i] + h * acc;
  }
}

using StageInput = void (*)(size_t, double, const double* __restrict, const double* const*, double* __restrict);
constexpr StageInput kStageInput[7] = {nullptr,          stage_input<1>, stage_input<2>, stage_input<3>,
                                       stage_input<4>, stage_input<5>, stage_input<6>};

// The weighted RMS norm of the error estimate h sum_j e_j k_j (e_1 = 0), weights at y.
double error_norm(size_t n, double h, double rtol, const double* __restrict atol, const double* __restrict y,
                  const double* const* k) {
  double sum = 0;
  for (size_t i = 0; i < n; ++i) {
    const double e = h * (kE[0] * k[0][i] + kE[2] * k[2][i] + kE[3] * k[3][i] + kE[4] * k[4][i] + kE[5] * k[5][i] +
                          kE[6] * k[6][i]);
    const double r = e / (rtol * std::fabs(y[i]) + atol[i]);
    sum += r * r;
  }
  return std::sqrt(sum / static_cast<double>(n));
}

}  // namespace

int DopriSession::attempt(double h, double* dsm) {
  const double* y = data(yn_);
  const double* k[7];
  for (int s = 0; s < 7; ++s) k[s] = data(k_[s]);
  for (int s = 1; s < 7; ++s) {
    N_Vector in = s == 6 ? ynew_.get() : stage_.get();
    kStageInput[s](n_, h, y, k, N_VGetArrayPointer(in));
    const int flag = rhs_(tn_ + kC[s] * h, in, k_[s].get(), user_data_);
    ++stats_.rhs_evals;
    if (flag < 0) return kRhsFail;
    if (flag > 0) {
      *dsm = kFailedNorm;
      return 0;
    }
  }
  *dsm = error_norm(n_, h, rtol_, atol_.data(), y, k);
  if (!std::isfinite(*dsm)) *dsm = kFailedNorm;
  return 0;
}

double DopriSession::propose(double h, double dsm) const {
  const double e1 = std::max(kBias * dsm, kTiny), e2 = std::max(ehist_, kTiny);
  double hacc = kSafety * h * std::pow(e1, kK1) * std::pow(e2, kK2);
  hacc = std::max(std::min(hacc, etamax_ * h), kEtaMin * h);
  if (dsm <= 1.0 && hacc > h * kKeepLow * (1 - kUround) && hacc < h * kKeepHigh * (1 + kUround)) hacc = h;
  if (hmax_ > 0) hacc = std::min(hacc, hmax_);
  return hacc;
}

int DopriSession::step() {
  double h = hmax_ > 0 ? std::min(h_, hmax_) : h_;
  bool to_stop = tstop_set_ && tn_ + h >= tstop_;
  if (to_stop) h = tstop_ - tn_;
  for (int failures = 0;;) {
    if (h <= 4 * kUround * std::max(std::fabs(tn_), 1.0) && !to_stop) return kErrFailure;
    double dsm = 0;
    if (const int flag = attempt(h, &dsm); flag < 0) return flag;
    const double hnew = propose(h, dsm);
    if (dsm <= 1.0) {
      told_ = tn_;
      tn_ = to_stop ? tstop_ : tn_ + h;
      h_last_ = h;
      std::swap(yold_, yn_);
      std::swap(yn_, ynew_);
      std::swap(fold_, k_[0]);
      std::swap(k_[0], k_[6]);
      ehist_ = kBias * dsm;
      etamax_ = kGrowth;
      h_ = hnew;
      ++stats_.steps;
      return 0;
    }
    ++stats_.error_test_failures;
    if (++failures >= kMaxErrorFailures) return kErrFailure;
    etamax_ = 1.0;
    double eta = hnew / h;
    if (failures >= kSmallFailures) eta = std::min(eta, kEtaMaxFail);
    h *= eta;
    to_stop = false;
  }
}

int DopriSession::advance(double tout, double* t, int itask) {
  *t = tn_;
  if (!started_)
    if (const int flag = start(tout); flag < 0) return flag;
  if (tstop_set_ && tstop_ < tn_ - roundoff()) return kIllInput;
  auto hand_out = [&](double when) {
    if (when == tn_) std::copy(data(yn_), data(yn_) + n_, data(y_));
    else interpolate(when, 0, data(y_));
    *t = tret_last_ = when;
  };
  bool stepped = false;
  for (long steps = 0;; ++steps) {
    const bool at_tout = itask == CV_NORMAL && tout <= tn_;
    const double thi = at_tout ? tout : tn_;
    if (root_ && thi > tlo_ && search_roots(thi)) {
      hand_out(troot_);
      return CV_ROOT_RETURN;
    }
    if (at_tout) {
      hand_out(tout);
      return CV_SUCCESS;
    }
    if (tstop_set_ && tn_ >= tstop_ - roundoff()) {
      hand_out(tn_);
      *t = tret_last_ = tstop_;
      tstop_set_ = false;
      return CV_TSTOP_RETURN;
    }
    // One-step mode returns after a step, or at once with the end of a step taken before and
    // not yet returned (after a root inside it), as CVODES does.
    if (itask == CV_ONE_STEP && (stepped || tn_ > tret_last_)) {
      hand_out(tn_);
      return CV_SUCCESS;
    }
    if (steps >= max_steps_) {
      hand_out(tn_);
      return kTooMuchWork;
    }
    if (const int flag = step(); flag < 0) {
      hand_out(tn_);
      return flag;
    }
    stepped = true;
  }
}

void DopriSession::eval_roots(double t, std::vector<double>& g) {
  if (t == tn_) {
    root_(t, yn_.get(), g.data(), user_data_);
    return;
  }
  interpolate(t, 0, data(stage_));
  root_(t, stage_.get(), g.data(), user_data_);
}

int DopriSession::crossing(size_t i, double glo, double ghi) const {
  const int before = glo != 0 ? sign_of(glo) : last_sign_[i];
  if (before == 0 || ghi * before > 0) return 0;
  const int dir = before < 0 ? 1 : -1;
  return dirs_[i] == 0 || dirs_[i] == dir ? dir : 0;
}

// CVODES' root search (cvRootfind): the Illinois variant of the secant method on the
// component whose crossing comes first, down to 100 ulp of the time; the root returned is the
// bracket's right end, where the crossing components have changed sign (or are 0).
bool DopriSession::search_roots(double thi) {
  eval_roots(thi, ghi_);
  const size_t m = dirs_.size();
  auto settle = [&](const std::vector<double>& glo, const std::vector<double>& g) {
    for (size_t i = 0; i < m; ++i) {
      const int before = glo[i] != 0 ? sign_of(glo[i]) : last_sign_[i];
      last_sign_[i] = g[i] != 0 ? sign_of(g[i]) : -before;  // a crossing onto 0 counts as crossed
    }
  };
  auto any_crossing = [&](const std::vector<double>& glo, const std::vector<double>& g) {
    for (size_t i = 0; i < m; ++i)
      if (crossing(i, glo[i], g[i])) return true;
    return false;
  };
  if (!any_crossing(glo_, ghi_)) {
    settle(glo_, ghi_);
    glo_ = ghi_;
    tlo_ = thi;
    return false;
  }
  double tlo = tlo_, th = thi, alpha = 1.0;
  const double ttol = 100 * kUround * (std::fabs(tn_) + std::fabs(h_last_));
  int side = 0;
  while (th - tlo > ttol) {
    size_t imax = 0;
    double best = -1.0;
    for (size_t i = 0; i < m; ++i)
      if (crossing(i, glo_[i], ghi_[i])) {
        const double frac = std::fabs(ghi_[i] / (ghi_[i] - alpha * glo_[i]));
        if (frac > best) best = frac, imax = i;
      }
    double tmid = th - (th - tlo) * std::min(1.0, best);
    if (glo_[imax] == 0 || !std::isfinite(tmid)) tmid = 0.5 * (tlo + th);
    const double span = th - tlo;
    if (tmid - tlo < 0.5 * ttol) {
      const double frac = span / ttol > 5 ? 0.1 : 0.5 / (span / ttol);
      tmid = tlo + frac * span;
    } else if (th - tmid < 0.5 * ttol) {
      const double frac = span / ttol > 5 ? 0.1 : 0.5 / (span / ttol);
      tmid = th - frac * span;
    }
    eval_roots(tmid, gmid_);
    const int prev = side;
    if (any_crossing(glo_, gmid_)) {
      th = tmid;
      ghi_ = gmid_;
      side = 1;
    } else {
      settle(glo_, gmid_);
      glo_ = gmid_;
      tlo = tmid;
      side = 2;
    }
    alpha = prev == side ? (side == 2 ? alpha * 2 : alpha * 0.5) : 1.0;
  }
  for (size_t i = 0; i < m; ++i) found_[i] = crossing(i, glo_[i], ghi_[i]);
  settle(glo_, ghi_);
  glo_ = ghi_;
  tlo_ = troot_ = th;
  return true;
}

void DopriSession::root_info(int* found) { std::copy(found_.begin(), found_.end(), found); }

// The cubic Hermite polynomial through (told_, yold_, fold_) and (tn_, yn_, k_[0]), or its k-th
// derivative; before the first step, y and f at tn_.
void DopriSession::interpolate(double t, int k, double* out) const {
  const double *y1 = data(yn_), *f1 = data(k_[0]);
  if (h_last_ == 0.0) {
    for (size_t i = 0; i < n_; ++i) out[i] = k == 0 ? y1[i] : (k == 1 ? f1[i] : 0.0);
    return;
  }
  const double h = h_last_, s = (t - told_) / h, s2 = s * s;
  double c0, c1, d0, d1;  // weights of y0, y1 (over h^k) and of f0, f1 (over h^(k-1))
  switch (k) {
    case 0: c0 = 2 * s2 * s - 3 * s2 + 1, c1 = -2 * s2 * s + 3 * s2, d0 = (s2 * s - 2 * s2 + s) * h, d1 = (s2 * s - s2) * h; break;
    case 1: c0 = (6 * s2 - 6 * s) / h, c1 = -c0, d0 = 3 * s2 - 4 * s + 1, d1 = 3 * s2 - 2 * s; break;
    case 2: c0 = (12 * s - 6) / (h * h), c1 = -c0, d0 = (6 * s - 4) / h, d1 = (6 * s - 2) / h; break;
    default: c0 = 12 / (h * h * h), c1 = -c0, d0 = 6 / (h * h), d1 = 6 / (h * h); break;
  }
  const double *y0 = data(yold_), *f0 = data(fold_);
  for (size_t i = 0; i < n_; ++i) out[i] = c0 * y0[i] + c1 * y1[i] + d0 * f0[i] + d1 * f1[i];
}

int DopriSession::dky(double t, int k, N_Vector out) {
  if (k < 0 || k > 3) return kBadT;
  const double fuzz = 100 * kUround * (std::fabs(tn_) + std::fabs(h_last_));
  if (t < told_ - fuzz || t > tn_ + fuzz) return kBadT;
  interpolate(t, k, N_VGetArrayPointer(out));
  return 0;
}

std::string DopriSession::flag_name(int flag) const {
  switch (flag) {
    case kTooMuchWork: return "TOO_MUCH_WORK";
    case kErrFailure: return "ERR_FAILURE";
    case kRhsFail: return "RHSFUNC_FAIL";
    case kIllInput: return "ILL_INPUT (stop time behind the current time)";
    case kBadT: return "BAD_T";
    default: return "flag " + std::to_string(flag);
  }
}

}  // namespace phasmid::solver
