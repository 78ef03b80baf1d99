#pragma once
// One CVODES integrator and everything it owns (AMICI's "Solver" without the model): the
// CVODES memory, the state and sensitivity N_Vectors, the Jacobian matrix, the linear solver,
// tolerances and SolverOptions' step controls. Shared by the
// whole-system driver (one session) and the partitioned driver (one session per part).
//
// Contract:
//  - Every SUNDIALS object is released by the destructor, also when a constructor or set-up
//    call throws half-way (each handle is a unique_ptr with its SUNDIALS destructor).
//  - Failing set-up calls throw SolverError("CVODES setup failed in <call> (flag N)").
//  - restart(t) is the restart at a switch of the right-hand side (a breakpoint or a
//    triggered command time): CVodeReInit from the current y(), and CVodeSensReInit from the
//    current s() with sensitivities. CVODES' counters are summed over restarts (stats()).
//  - The SUNContext outlives every session made with it (SundialsContext, declared first).
#include <cvodes/cvodes.h>
#include <sundials/sundials_context.h>

#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "solver/integrator_session.hpp"
#include "solver/solver_options.hpp"
#include "solver/solver_result.hpp"

namespace phasmid::solver {

// Throws SolverError("CVODES setup failed in <what> (flag N)") for a negative flag.
void check_cvodes(int flag, const char* what);
// CVODES' name of a return flag ("CV_TOO_MUCH_WORK"; CVodeGetReturnFlagName's string freed).
std::string cvodes_flag_name(int flag);
// What to try after a failed integration, for the error message: "(try --set on the offending
// parameter, tighter tolerances, ...)"; tighter tolerances only while rtol is above
// kTightestUsefulRtol, below which CVODES cannot resolve more digits of a double.
inline constexpr double kTightestUsefulRtol = 1e-13;
std::string failure_advice(const SolverOptions& options, bool partitioned);
// Adds the counters of `from` (steps, evaluations, failures, iterations, setups) to `into`.
void add_counters(SolverStats& into, const SolverStats& from);

// Owns one SUNContext for the sessions of a run.
class SundialsContext {
 public:
  SundialsContext();
  ~SundialsContext();
  SundialsContext(const SundialsContext&) = delete;
  SundialsContext& operator=(const SundialsContext&) = delete;
  SUNContext get() const { return ctx_; }

 private:
  SUNContext ctx_ = nullptr;
};

// Newton's linear systems (BDF): dense LU, band LU (half bandwidth) or KLU (sparse, nnz entries).
enum class LinearSystem { Dense, Band, Sparse };

class CvodesSession : public IntegratorSession {
 public:
  // The integrator at t = 0 from y0 (n states) for rhs(t, y, ydot, user_data): BDF, scalar
  // tolerances, step options and a silent error handler (phasmid reports failures).
  CvodesSession(SUNContext ctx, const SolverOptions& options, const double* y0, size_t n, CVRhsFn rhs,
                void* user_data);
  ~CvodesSession() override;
  CvodesSession(const CvodesSession&) = delete;
  CvodesSession& operator=(const CvodesSession&) = delete;

  // Newton with the chosen linear system and Jacobian `jac`; phasmid's compiled matrix kernels
  // for dense and sparse matrices.
  void set_linear_solver(LinearSystem kind, long half_bandwidth, long nnz, CVLsJacFn jac);
  // Forward sensitivities of s0.size() parameters from s0[j] (n values each): the batched
  // right-hand side `all` for more than one parameter, `one` for a single one; pbar scales the
  // sensitivity tolerances (SolverOptions::sensitivity_*).
  void init_sensitivities(const std::vector<std::vector<double>>& s0, CVSensRhsFn all, CVSensRhs1Fn one,
                          const std::vector<double>& pbar);
  // Root functions g (directions.size() of them) located in the given directions.
  void init_roots(const std::vector<int>& directions, CVRootFn g) override;
  void set_stop_time(double t) override;
  void set_state_atol(const std::vector<double>& atol) override;
  // CVode towards tout in CV_NORMAL or CV_ONE_STEP mode; returns CVODES' flag (negative: failed).
  int advance(double tout, double* t, int itask) override;
  // The sensitivities at the time last returned, into s().
  void fetch_sensitivities() override;
  void restart(double t) override;
  void root_info(int* found) override;
  int dky(double t, int k, N_Vector out) override { return CVodeGetDky(mem(), t, k, out); }
  int interpolation_degree() override;  // the order of the last step (Nordsieck array)
  double current_time() override;
  double last_step() override;
  std::string flag_name(int flag) const override { return cvodes_flag_name(flag); }
  const char* package() const override { return "CVODES"; }

  void* mem() const { return mem_.get(); }
  N_Vector y() const override { return y_.get(); }
  N_Vector* s() const override { return yS_.get(); }
  int num_sensitivities() const { return ns_; }
  long total_steps() const override;
  SolverStats stats() const override;

 private:
  struct Free {
    void operator()(void* mem) const;
    void operator()(N_Vector v) const;
    void operator()(SUNMatrix A) const;
    void operator()(SUNLinearSolver ls) const;
  };
  template <class Handle>
  using Owned = std::unique_ptr<std::remove_pointer_t<Handle>, Free>;
  struct FreeArray {
    // No default member initializer: with one, unique_ptr could not default-construct this
    // deleter while CvodesSession is still incomplete.
    int n;
    void operator()(N_Vector* v) const;
  };
  const SolverOptions options_;  // a copy: callers may pass a temporary adjusted copy
  SUNContext ctx_;
  int ns_ = 0;
  // Destroyed in reverse order of declaration: the CVODES memory, then the linear solver and
  // matrix it used, then the vectors.
  Owned<N_Vector> y_;
  std::unique_ptr<N_Vector, FreeArray> yS_;
  Owned<SUNMatrix> A_;
  Owned<SUNLinearSolver> LS_;
  std::unique_ptr<void, Free> mem_;
  SolverStats before_restarts_;  // CVodeReInit resets CVODES' counters
};

}  // namespace phasmid::solver
