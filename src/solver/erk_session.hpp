#pragma once
// One explicit adaptive Runge-Kutta integrator (ARKODE's ERKStep, SUNDIALS 6.4) behind the
// IntegratorSession interface, next to CvodesSession: no Jacobian, no Newton iteration, no
// linear solves; the embedded pair of the chosen Butcher table controls the step
// (SolverOptions::integrator, IntegratorKind::Erk*). Events by ERKStepRootInit, restarts at
// switches by ERKStepReset, the last step's Hermite interpolant for outputs, events and the
// partitioned driver's coupling polynomials. A right-hand side that reports a recoverable
// failure (returns 1, a non-finite trial stage) makes ERKStep retry a smaller step, as in CVODES.
//
// Contract:
//  - Every SUNDIALS object is released by the destructor, also when a set-up call throws.
//  - Failing set-up calls throw SolverError("ARKODE setup failed in <call> (flag N)").
//  - Counters (steps, right-hand sides, error-test failures) are summed over restarts;
//    Jacobian, Newton and linear-setup counters stay 0.
//  - No forward sensitivities (they run on CVODES BDF: Simulator::run).
#include <memory>
#include <string>
#include <vector>

#include "solver/integrator_session.hpp"

namespace phasmid::solver {

// The session of an explicit integrator kind: phasmid's DopriSession for Dopri5, else ErkSession.
std::unique_ptr<IntegratorSession> make_explicit_session(SUNContext ctx, const SolverOptions& options, const double* y0,
                                                         size_t n, CVRhsFn rhs, void* user_data);

class ErkSession : public IntegratorSession {
 public:
  // The integrator at t = 0 from y0 (n states) for rhs(t, y, ydot, user_data) with the table
  // of options.integrator (an explicit Runge-Kutta kind), scalar tolerances and step options.
  ErkSession(SUNContext ctx, const SolverOptions& options, const double* y0, size_t n, CVRhsFn rhs, void* user_data);
  ~ErkSession() override;
  ErkSession(const ErkSession&) = delete;
  ErkSession& operator=(const ErkSession&) = delete;

  void init_roots(const std::vector<int>& directions, CVRootFn g) override;
  void set_stop_time(double t) override;
  void set_state_atol(const std::vector<double>& atol) override;
  int advance(double tout, double* t, int itask) override;
  void restart(double t) override;
  void root_info(int* found) override;
  int dky(double t, int k, N_Vector out) override;
  int interpolation_degree() override { return degree_; }
  double current_time() override;
  double last_step() override;
  std::string flag_name(int flag) const override;
  const char* package() const override { return "ARKODE"; }

  N_Vector y() const override { return y_.get(); }
  long total_steps() const override;
  SolverStats stats() const override;

 private:
  struct FreeMemory {
    void operator()(void* mem) const;
  };
  void* mem() const { return mem_.get(); }
  // ARKODE calls these with the session as user data; they call the driver's functions.
  static int rhs_trampoline(double t, N_Vector y, N_Vector ydot, void* self);
  static int root_trampoline(double t, N_Vector y, double* g, void* self);
  CVRhsFn rhs_;
  CVRootFn root_ = nullptr;
  void* user_data_;
  double rtol_;
  OwnedVector y_;
  std::unique_ptr<void, FreeMemory> mem_;
  int degree_ = 3;
};

}  // namespace phasmid::solver
