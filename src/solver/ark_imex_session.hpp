#pragma once
// An additive Runge-Kutta (IMEX) integrator, ARKODE's ARKStep (SUNDIALS 6.4), behind the
// IntegratorSession interface, for the networks whose step an explicit method bounds by the
// stiffness of single states (docs/solver.md "IMEX"): the implicit part is
// f_I = -kappa(y) * (y - c) with kappa from a StiffRates function and constant offsets c
// (model/stiff_rates.hpp), the explicit part f - f_I.
// The Newton matrix I - gamma df_I/dy is taken as its diagonal 1 + gamma kappa, so a linear
// solve is one multiplication per state (a matrix-embedded SUNLinearSolver); kappa is taken at
// every stage's predicted state. Kennedy-Carpenter ARK4(3)6L[2]SA or ARK5(4)8L[2]SA tables.
// Measured slower than Dormand-Prince on the networks at matched accuracy (bench/results
// "IMEX against Dormand-Prince"), so no [simulation] integrator selects it; bench/bench_imex.cpp.
//
// Contract: as ErkSession (destructor releases everything, set-up failures throw SolverError
// naming the ARKODE call, counters summed over restarts, no sensitivities). rhs_evals counts
// the f_E evaluations (one full right-hand side each); Newton iterations and convergence
// failures are counted; linear set-ups stay 0 (the diagonal is taken in each solve).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "solver/integrator_session.hpp"

namespace phasmid::solver {

// kappa(t, y) per state (1/ms, >= 0; 0: the state is explicit only).
using StiffRates = std::function<void(double t, const double* y, double* kappa)>;

struct ImexOptions {
  int order = 4;  // 4 or 5: the Kennedy-Carpenter pair of that order
  // One Newton iteration per stage without a convergence test (ARKStepSetLinear): exact only
  // for a kappa that does not depend on y; measured to lose accuracy here (bench/results).
  bool linearly_implicit = false;
};

class ArkImexSession : public IntegratorSession {
 public:
  ArkImexSession(SUNContext ctx, const SolverOptions& options, const double* y0, size_t n, CVRhsFn rhs,
                 void* user_data, StiffRates kappa, std::vector<double> offsets, const ImexOptions& imex = {});
  ~ArkImexSession() override;
  ArkImexSession(const ArkImexSession&) = delete;
  ArkImexSession& operator=(const ArkImexSession&) = delete;

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
  struct FreeSolver {
    void operator()(SUNLinearSolver ls) const;
  };
  void* mem() const { return mem_.get(); }
  // kappa at (t, y), cached for the last state (ARKStep evaluates f_E and f_I at the same stage).
  const double* kappa_at(double t, const double* y);
  static int fe_trampoline(double t, N_Vector y, N_Vector ydot, void* self);
  static int fi_trampoline(double t, N_Vector y, N_Vector ydot, void* self);
  static int root_trampoline(double t, N_Vector y, double* g, void* self);
  static int ls_solve(SUNLinearSolver ls, SUNMatrix, N_Vector x, N_Vector b, double tol);
  CVRhsFn rhs_;
  CVRootFn root_ = nullptr;
  void* user_data_;
  StiffRates rates_;
  size_t n_;
  std::vector<double> offsets_, kappa_, kappa_y_, newton_diag_;
  double newton_t_ = -1e300, newton_gamma_ = 0.0;  // the stage newton_diag_ belongs to
  double kappa_t_ = -1e300;
  OwnedVector y_;
  std::unique_ptr<void, FreeMemory> mem_;
  std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, FreeSolver> ls_;
  int degree_ = 3;
};

}  // namespace phasmid::solver
