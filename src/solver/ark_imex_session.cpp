#include "solver/ark_imex_session.hpp"

#include <arkode/arkode.h>
#include <arkode/arkode_arkstep.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_linearsolver.h>

#include <algorithm>
#include <cstring>

#include "common/error.hpp"

namespace phasmid::solver {

namespace {

void check_arkode(int flag, const char* what) {
  if (flag < 0) throw SolverError(std::string("ARKODE setup failed in ") + what + " (flag " + std::to_string(flag) + ")");
}

}  // namespace

void ArkImexSession::FreeMemory::operator()(void* mem) const { ARKStepFree(&mem); }
void ArkImexSession::FreeSolver::operator()(SUNLinearSolver ls) const { SUNLinSolFreeEmpty(ls); }

ArkImexSession::ArkImexSession(SUNContext ctx, const SolverOptions& options, const double* y0, size_t n, CVRhsFn rhs,
                               void* user_data, StiffRates kappa, std::vector<double> offsets, const ImexOptions& imex)
    : rhs_(rhs),
      user_data_(user_data),
      rates_(std::move(kappa)),
      n_(n),
      offsets_(std::move(offsets)),
      kappa_(n),
      kappa_y_(n),
      newton_diag_(n) {
  if (offsets_.size() != n) throw Error("internal: ArkImexSession needs one offset per state");
  if (imex.order != 4 && imex.order != 5) throw Error("internal: ArkImexSession has the orders 4 and 5");
  y_.reset(new_state_vector(ctx, options, y0, n));
  mem_.reset(ARKStepCreate(fe_trampoline, fi_trampoline, 0.0, y(), ctx));
  if (!mem_) throw SolverError("ARKStepCreate failed");
  check_arkode(ARKStepSetErrHandlerFn(mem(), [](int, const char*, const char*, char*, void*) {}, nullptr), "silence");
  if (imex.order == 4)
    check_arkode(ARKStepSetTableNum(mem(), ARKODE_ARK436L2SA_DIRK_6_3_4, ARKODE_ARK436L2SA_ERK_6_3_4), "ARKStepSetTableNum");
  else
    check_arkode(ARKStepSetTableNum(mem(), ARKODE_ARK548L2SA_DIRK_8_4_5, ARKODE_ARK548L2SA_ERK_8_4_5), "ARKStepSetTableNum");
  check_arkode(ARKStepSStolerances(mem(), options.rtol, options.atol), "ARKStepSStolerances");
  check_arkode(ARKStepSetUserData(mem(), this), "ARKStepSetUserData");
  check_arkode(ARKStepSetMaxNumSteps(mem(), options.max_steps), "ARKStepSetMaxNumSteps");
  check_arkode(ARKStepSetInterpolantDegree(mem(), degree_), "ARKStepSetInterpolantDegree");
  check_arkode(ARKStepSetMaxErrTestFails(mem(), 50), "ARKStepSetMaxErrTestFails");
  if (options.max_step_ms > 0) check_arkode(ARKStepSetMaxStep(mem(), options.max_step_ms), "ARKStepSetMaxStep");

  ls_.reset(SUNLinSolNewEmpty(ctx));
  if (!ls_) throw SolverError("SUNLinSolNewEmpty failed");
  ls_->content = this;
  ls_->ops->gettype = [](SUNLinearSolver) { return SUNLINEARSOLVER_MATRIX_EMBEDDED; };
  ls_->ops->getid = [](SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; };
  ls_->ops->solve = ls_solve;
  check_arkode(ARKStepSetLinearSolver(mem(), ls_.get(), nullptr), "ARKStepSetLinearSolver");
  if (imex.linearly_implicit) check_arkode(ARKStepSetLinear(mem(), 1), "ARKStepSetLinear");
  // ls_solve uses the current gamma: no rescaling of its solution by ARKODE.
  ARKStepSetLinearSolutionScaling(mem(), SUNFALSE);
}

ArkImexSession::~ArkImexSession() {
  mem_.reset();  // ARKStepFree before the linear solver it references
}

const double* ArkImexSession::kappa_at(double t, const double* y) {
  if (t != kappa_t_ || std::memcmp(y, kappa_y_.data(), n_ * sizeof(double)) != 0) {
    rates_(t, y, kappa_.data());
    std::copy(y, y + n_, kappa_y_.begin());
    kappa_t_ = t;
  }
  return kappa_.data();
}

// f_E = f + kappa (y - c). A recoverable right-hand-side failure becomes huge finite slopes, as in
// ErkSession (ARKStep takes the flag as fatal).
int ArkImexSession::fe_trampoline(double t, N_Vector y, N_Vector ydot, void* self) {
  auto* s = static_cast<ArkImexSession*>(self);
  const int flag = s->rhs_(t, y, ydot, s->user_data_);
  if (flag < 0) return flag;
  double* f = N_VGetArrayPointer(ydot);
  if (flag > 0) {
    std::fill(f, f + s->n_, 1e150);
    return 0;
  }
  const double* x = N_VGetArrayPointer(y);
  const double* k = s->kappa_at(t, x);
  for (size_t i = 0; i < s->n_; ++i) f[i] += k[i] * (x[i] - s->offsets_[i]);
  return 0;
}

int ArkImexSession::fi_trampoline(double t, N_Vector y, N_Vector ydot, void* self) {
  auto* s = static_cast<ArkImexSession*>(self);
  const double* x = N_VGetArrayPointer(y);
  const double* k = s->kappa_at(t, x);
  double* f = N_VGetArrayPointer(ydot);
  for (size_t i = 0; i < s->n_; ++i) f[i] = -k[i] * (x[i] - s->offsets_[i]);
  return 0;
}

// Newton matrix diagonal 1 + gamma kappa at the stage's predicted state (the cache makes that
// one kappa per stage). Taken here rather than at ARKODE's set-up calls, which a
// matrix-embedded solver does not get at every stage, with the current gamma.
int ArkImexSession::ls_solve(SUNLinearSolver ls, SUNMatrix, N_Vector x, N_Vector b, double) {
  auto* s = static_cast<ArkImexSession*>(ls->content);
  double tcur = 0.0, gamma = 0.0;
  N_Vector zpred = nullptr, z = nullptr, Fi = nullptr, sdata = nullptr;
  void* ud = nullptr;
  if (ARKStepGetNonlinearSystemData(s->mem(), &tcur, &zpred, &z, &Fi, &gamma, &sdata, &ud) < 0) return -1;
  if (tcur != s->newton_t_ || gamma != s->newton_gamma_) {
    const double* k = s->kappa_at(tcur, N_VGetArrayPointer(zpred));
    for (size_t i = 0; i < s->n_; ++i) s->newton_diag_[i] = 1.0 / (1.0 + gamma * k[i]);
    s->newton_t_ = tcur;
    s->newton_gamma_ = gamma;
  }
  const double* bb = N_VGetArrayPointer(b);
  double* xx = N_VGetArrayPointer(x);
  for (size_t i = 0; i < s->n_; ++i) xx[i] = bb[i] * s->newton_diag_[i];
  return 0;
}

int ArkImexSession::root_trampoline(double t, N_Vector y, double* g, void* self) {
  auto* s = static_cast<ArkImexSession*>(self);
  return s->root_(t, y, g, s->user_data_);
}

void ArkImexSession::init_roots(const std::vector<int>& directions, CVRootFn g) {
  if (directions.empty()) return;
  std::vector<int> dirs = directions;
  root_ = g;
  check_arkode(ARKStepRootInit(mem(), static_cast<int>(dirs.size()), root_trampoline), "ARKStepRootInit");
  check_arkode(ARKStepSetRootDirection(mem(), dirs.data()), "ARKStepSetRootDirection");
  ARKStepSetNoInactiveRootWarn(mem());
}

void ArkImexSession::set_state_atol(const std::vector<double>&) {
  throw Error("internal: per-state absolute tolerances are not implemented for the IMEX bench integrator");
}

void ArkImexSession::set_stop_time(double t) { check_arkode(ARKStepSetStopTime(mem(), t), "ARKStepSetStopTime"); }

int ArkImexSession::advance(double tout, double* t, int itask) { return ARKStepEvolve(mem(), tout, y(), t, itask); }

void ArkImexSession::restart(double t) { check_arkode(ARKStepReset(mem(), t, y()), "ARKStepReset"); }

void ArkImexSession::root_info(int* found) { check_arkode(ARKStepGetRootInfo(mem(), found), "ARKStepGetRootInfo"); }

int ArkImexSession::dky(double t, int k, N_Vector out) { return ARKStepGetDky(mem(), t, k, out); }

double ArkImexSession::current_time() {
  double t = 0.0;
  ARKStepGetCurrentTime(mem(), &t);
  return t;
}

double ArkImexSession::last_step() {
  double h = 0.0;
  ARKStepGetLastStep(mem(), &h);
  return h;
}

std::string ArkImexSession::flag_name(int flag) const { return take_flag_name(ARKStepGetReturnFlagName(flag), flag); }

long ArkImexSession::total_steps() const {
  long v = 0;
  ARKStepGetNumSteps(mem(), &v);
  return v;
}

SolverStats ArkImexSession::stats() const {
  SolverStats s;
  long fe = 0, fi = 0;
  ARKStepGetNumSteps(mem(), &s.steps);
  ARKStepGetNumRhsEvals(mem(), &fe, &fi);
  s.rhs_evals = fe;
  ARKStepGetNumErrTestFails(mem(), &s.error_test_failures);
  ARKStepGetNumNonlinSolvIters(mem(), &s.newton_iterations);
  ARKStepGetNumNonlinSolvConvFails(mem(), &s.newton_failures);
  ARKStepGetNumLinSolvSetups(mem(), &s.linear_setups);
  return s;
}

}  // namespace phasmid::solver
