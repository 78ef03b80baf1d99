#pragma once
// Dormand-Prince 5(4) written for phasmid's small systems (IntegratorKind::Dopri5, "dopri5"),
// behind the IntegratorSession interface next to CvodesSession.
//
// Why a stepper of our own: on the walking networks' parts (14-26 states) ARKODE's per-step
// work outside the right-hand side (vector kernels called one combination at a time through
// N_Vector operations, the step and stop-time logic) weighs as much as a large part of the
// right-hand side (docs/performance.md "What the build contributes"). Here each stage is one
// fused loop over the states, and the step, its error norm and the dense output read the same
// few arrays.
//
// The method is ARKODE's: the same Butcher table (first same as last: six right-hand sides
// per accepted step), the error weights 1 / (rtol |y_n| + atol_i) at the step's start, ERKStep's
// default PI controller (k1 0.8, k2 0.31 over the embedding's order 4; bias 1.2, safety 0.99,
// growth 25, 10 000 on the first step, step kept when the proposal is 1-1.5 times it, at
// least a tenth and after two failures at most 0.3 of it after a rejected step),
// its first-step estimate, the cubic Hermite interpolant of the step's end values and slopes,
// and CVODES' Illinois root search on it. So it takes ARKODE's steps up to rounding.
//
// Contract:
//  - advance(tout, t, itask) returns 0 (tout reached in normal mode, or one step taken in
//    one-step mode; after a root inside the last step, its end without a new step), 1 (the stop time reached: y() is y(tstop), the stop is then cleared),
//    2 (a root: y() is y(t_root); the next call returns the step's further roots first),
//    or a negative flag: -1 more than max_steps steps in this call, -3 repeated error-test
//    failures (50) or a step below the time's resolution, -8 the right-hand side failed
//    unrecoverably, -22 a stop time behind the current time, -25 dky outside the last step.
//  - A right-hand side returning > 0 (a non-finite trial stage) rejects the step, which is
//    retried at a tenth of its size.
//  - restart(t) restarts from y() at t: slopes, first step and root signs are taken afresh;
//    tolerances, roots, counters and the stop time stay.
//  - No forward sensitivities.
#include <cmath>
#include <limits>
#include <vector>

#include "solver/integrator_session.hpp"

namespace phasmid::solver {

class DopriSession : public IntegratorSession {
 public:
  DopriSession(SUNContext ctx, const SolverOptions& options, const double* y0, size_t n, CVRhsFn rhs, void* user_data);

  void init_roots(const std::vector<int>& directions, CVRootFn g) override;
  void set_stop_time(double t) override;
  void set_state_atol(const std::vector<double>& atol) override;
  int advance(double tout, double* t, int itask) override;
  void restart(double t) override;
  void root_info(int* found) override;
  int dky(double t, int k, N_Vector out) override;
  int interpolation_degree() override { return 3; }
  double current_time() override { return tn_; }
  double last_step() override { return h_last_; }
  std::string flag_name(int flag) const override;
  const char* package() const override { return "phasmid dopri5"; }

  N_Vector y() const override { return y_.get(); }
  long total_steps() const override { return stats_.steps; }
  SolverStats stats() const override { return stats_; }

 private:
  // The slopes, the root signs and the first step (towards tout) at (tn_, yn_); 0 or a
  // negative flag.
  int start(double tout);
  // One accepted step from tn_ (retrying rejected attempts); 0 or a negative flag.
  int step();
  // One attempt of size h: the stages, ynew_ and the weighted error norm (huge when a stage
  // failed recoverably); returns a negative flag on an unrecoverable failure, else 0.
  int attempt(double h, double* dsm);
  // The step size the controller proposes after an attempt of size h with error norm dsm.
  double propose(double h, double dsm) const;
  double initial_step(double tout);
  bool second_derivative_norm(double h, double* norm);
  // Roots in (tlo_, thi] on the last step's interpolant: true with troot_ and found_ set.
  bool search_roots(double thi);
  void eval_roots(double t, std::vector<double>& g);
  // Sign change of root i from (glo, its last sign) to ghi in a watched direction: +1 / -1 / 0.
  int crossing(size_t i, double glo, double ghi) const;
  void interpolate(double t, int k, double* out) const;
  double* data(const OwnedVector& v) const { return N_VGetArrayPointer(v.get()); }
  // Times closer than this to the current time are the same time (ARKODE's FUZZ_FACTOR 100).
  double roundoff() const { return 100 * std::numeric_limits<double>::epsilon() * (std::fabs(tn_) + std::fabs(h_)); }

  CVRhsFn rhs_;
  void* user_data_;
  size_t n_;
  double rtol_;
  std::vector<double> atol_;
  long max_steps_;
  double hmax_;
  OwnedVector y_, yn_, yold_, ynew_, stage_;
  OwnedVector k_[7];  // stage slopes; k_[0] = f(tn_, yn_), k_[6] = f(tn_ + h, ynew_)
  OwnedVector fold_;  // f at the last step's start
  double tn_ = 0.0, told_ = 0.0, h_ = 0.0, h_last_ = 0.0;
  double tret_last_ = 0.0;  // the time advance() last returned
  double ehist_ = 1.0;  // the last accepted step's biased error norm
  double etamax_ = 1e4;
  bool started_ = false;
  bool slope_current_ = false;  // k_[0] is f(tn_, yn_) before the start (taken at a restart)
  double tstop_ = 0.0;
  bool tstop_set_ = false;
  // Roots.
  CVRootFn root_ = nullptr;
  std::vector<int> dirs_, found_, last_sign_;
  std::vector<double> glo_, ghi_, gmid_;
  double tlo_ = 0.0, troot_ = 0.0;
  SolverStats stats_;
};

}  // namespace phasmid::solver
