#pragma once
// The integrator a driver advances (AMICI's "Solver" without the model): CVODES BDF
// (CvodesSession, solver/cvodes_session.hpp) or phasmid's own Dormand-Prince (DopriSession,
// solver/dopri_session.hpp). The whole-system and the partitioned driver see only this
// interface, so events, restarts at switches, triggers and the parts' interpolation work with
// either.
//
// Contract:
//  - advance() returns the package's flag with CVODES' values: 0 success, 1 stop time reached,
//    2 root found and the itask values 1 normal, 2 one step; negative flags are failures
//    (flag_name names them).
//  - restart(t) restarts the integrator from y() at t (a switch of the right-hand side);
//    counters are summed over restarts (stats()).
//  - dky(t, k, out) is the k-th derivative at t of the last step's interpolating polynomial
//    (k <= interpolation_degree()); a negative return means t is outside the last step.
//  - Sensitivities exist on CVODES only (CvodesSession::init_sensitivities).
#include <cvodes/cvodes.h>
#include <nvector/nvector_serial.h>

#include <cstdlib>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "common/error.hpp"
#include "solver/serial_kernels.hpp"
#include "solver/solver_options.hpp"
#include "solver/solver_result.hpp"

namespace phasmid::solver {

// A return flag's name from the package's malloc'ed string (freed here), or "flag N".
inline std::string take_flag_name(char* name, int flag) {
  std::string s = name ? name : "flag " + std::to_string(flag);
  std::free(name);
  return s;
}

// A session's state vector: a new serial vector holding y0, with phasmid's compiled kernels
// (the package's work vectors are clones of it and copy its ops table). The caller owns it.
inline N_Vector new_state_vector(SUNContext ctx, const double* y0, size_t n) {
  N_Vector y = N_VNew_Serial(static_cast<sunindextype>(n), ctx);
  if (!y) throw SolverError("N_VNew_Serial failed");
  install_serial_kernels(y);
  for (size_t i = 0; i < n; ++i) NV_Ith_S(y, i) = y0[i];
  return y;
}

class IntegratorSession {
 public:
  virtual ~IntegratorSession() = default;

  // Root functions g (directions.size() of them) located in the given directions.
  virtual void init_roots(const std::vector<int>& directions, CVRootFn g) = 0;
  virtual void set_stop_time(double t) = 0;
  // Absolute tolerances per state (instead of SolverOptions::atol for all); kept over restarts.
  virtual void set_state_atol(const std::vector<double>& atol) = 0;
  // Towards tout in normal (1) or one-step (2) mode; the flag as in the contract.
  virtual int advance(double tout, double* t, int itask) = 0;
  virtual void restart(double t) = 0;
  // Which roots the last root return found (+1 rising, -1 falling, 0 none), one per root.
  virtual void root_info(int* found) = 0;
  virtual int dky(double t, int k, N_Vector out) = 0;
  virtual int interpolation_degree() = 0;
  virtual double current_time() = 0;
  virtual double last_step() = 0;
  virtual std::string flag_name(int flag) const = 0;
  virtual const char* package() const = 0;  // "CVODES", "phasmid dopri5": the start of failure messages

  virtual N_Vector y() const = 0;
  // A scratch vector of the state's size (for dky), owned by the session.
  N_Vector work() {
    if (!work_) work_.reset(N_VClone(y()));
    return work_.get();
  }
  virtual long total_steps() const = 0;
  virtual SolverStats stats() const = 0;  // counters since the start, over restarts

  // Forward sensitivities (CVODES only; see CvodesSession).
  virtual N_Vector* s() const { return nullptr; }
  virtual void fetch_sensitivities() {}

 protected:
  struct DestroyVector {
    void operator()(N_Vector v) const { N_VDestroy(v); }
  };
  using OwnedVector = std::unique_ptr<std::remove_pointer_t<N_Vector>, DestroyVector>;
  // A clone of `like` holding `values` (e.g. per-state tolerances for the package).
  static OwnedVector vector_like(N_Vector like, const std::vector<double>& values) {
    OwnedVector v(N_VClone(like));
    for (size_t i = 0; i < values.size(); ++i) NV_Ith_S(v.get(), i) = values[i];
    return v;
  }

 private:
  OwnedVector work_;
};

}  // namespace phasmid::solver
