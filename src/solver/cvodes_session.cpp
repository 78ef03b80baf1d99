#include "solver/cvodes_session.hpp"

#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_band.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <cstdlib>
#include <utility>

#include "common/error.hpp"
#include "solver/matrix_kernels.hpp"

namespace phasmid::solver {

void check_cvodes(int flag, const char* what) {
  if (flag < 0) throw SolverError(std::string("CVODES setup failed in ") + what + " (flag " + std::to_string(flag) + ")");
}

std::string cvodes_flag_name(int flag) { return take_flag_name(CVodeGetReturnFlagName(flag), flag); }

std::string failure_advice(const SolverOptions& options, bool partitioned) {
  std::vector<std::string> tries = {"--set on the offending parameter"};
  if (options.rtol > kTightestUsefulRtol) tries.push_back("tighter tolerances");
  if (partitioned) tries.push_back("partitioned = false");
  std::string s = "(try " + tries[0];
  for (size_t i = 1; i < tries.size(); ++i) s += (i + 1 == tries.size() ? ", or " : ", ") + tries[i];
  return s + ")";
}

void add_counters(SolverStats& into, const SolverStats& from) {
  for (long SolverStats::*field : {&SolverStats::steps, &SolverStats::rhs_evals, &SolverStats::jac_evals,
                                   &SolverStats::error_test_failures, &SolverStats::newton_iterations,
                                   &SolverStats::newton_failures, &SolverStats::linear_setups})
    into.*field += from.*field;
}

SundialsContext::SundialsContext() { check_cvodes(SUNContext_Create(nullptr, &ctx_), "SUNContext_Create"); }
SundialsContext::~SundialsContext() {
  if (ctx_) SUNContext_Free(&ctx_);
}

void CvodesSession::Free::operator()(void* mem) const { CVodeFree(&mem); }
void CvodesSession::Free::operator()(N_Vector v) const { N_VDestroy(v); }
void CvodesSession::Free::operator()(SUNMatrix A) const { SUNMatDestroy(A); }
void CvodesSession::Free::operator()(SUNLinearSolver ls) const { SUNLinSolFree(ls); }
void CvodesSession::FreeArray::operator()(N_Vector* v) const { N_VDestroyVectorArray(v, n); }

CvodesSession::CvodesSession(SUNContext ctx, const SolverOptions& options, const double* y0, size_t n, CVRhsFn rhs,
                             void* user_data)
    : options_(options), ctx_(ctx) {
  y_.reset(new_state_vector(ctx, y0, n));
  mem_.reset(CVodeCreate(CV_BDF, ctx));
  if (!mem_) throw SolverError("CVodeCreate failed");
  check_cvodes(CVodeSetErrHandlerFn(mem(), [](int, const char*, const char*, char*, void*) {}, nullptr), "silence");
  check_cvodes(CVodeInit(mem(), rhs, 0.0, y()), "CVodeInit");
  check_cvodes(CVodeSStolerances(mem(), options.rtol, options.atol), "CVodeSStolerances");
  check_cvodes(CVodeSetUserData(mem(), user_data), "CVodeSetUserData");
  check_cvodes(CVodeSetMaxNumSteps(mem(), options.max_steps), "CVodeSetMaxNumSteps");
  if (options.max_step_ms > 0) check_cvodes(CVodeSetMaxStep(mem(), options.max_step_ms), "CVodeSetMaxStep");
}

CvodesSession::~CvodesSession() = default;

void CvodesSession::set_linear_solver(LinearSystem kind, long half_bandwidth, long nnz, CVLsJacFn jac) {
  const sunindextype n = N_VGetLength(y());
  if (kind == LinearSystem::Band) {
    A_.reset(SUNBandMatrix(n, half_bandwidth, half_bandwidth, ctx_));
    LS_.reset(SUNLinSol_Band(y(), A_.get(), ctx_));
  } else if (kind == LinearSystem::Sparse) {
    A_.reset(SUNSparseMatrix(n, n, static_cast<sunindextype>(nnz), CSC_MAT, ctx_));
    LS_.reset(SUNLinSol_KLU(y(), A_.get(), ctx_));
    install_sparse_kernels(A_.get());
  } else {
    A_.reset(SUNDenseMatrix(n, n, ctx_));
    LS_.reset(SUNLinSol_Dense(y(), A_.get(), ctx_));
    install_dense_kernels(A_.get(), LS_.get());
  }
  if (!A_ || !LS_) throw SolverError("CVODES setup failed: matrix or linear solver not created");
  check_cvodes(CVodeSetLinearSolver(mem(), LS_.get(), A_.get()), "CVodeSetLinearSolver");
  if (jac) check_cvodes(CVodeSetJacFn(mem(), jac), "CVodeSetJacFn");
}

void CvodesSession::init_sensitivities(const std::vector<std::vector<double>>& s0, CVSensRhsFn all, CVSensRhs1Fn one,
                                       const std::vector<double>& pbar) {
  ns_ = static_cast<int>(s0.size());
  const size_t n = static_cast<size_t>(N_VGetLength(y()));
  yS_ = std::unique_ptr<N_Vector, FreeArray>(N_VCloneVectorArray(ns_, y()), FreeArray{ns_});
  for (int j = 0; j < ns_; ++j)
    for (size_t i = 0; i < n; ++i) NV_Ith_S(yS_.get()[j], i) = s0[static_cast<size_t>(j)][i];
  const bool staggered = options_.sensitivity_method == SensitivityMethod::Staggered;
  const int method = staggered ? CV_STAGGERED : CV_SIMULTANEOUS;
  if (ns_ > 1)
    check_cvodes(CVodeSensInit(mem(), ns_, method, all, s()), "CVodeSensInit");
  else
    check_cvodes(CVodeSensInit1(mem(), ns_, method, one, s()), "CVodeSensInit1");
  check_cvodes(CVodeSetSensParams(mem(), nullptr, const_cast<double*>(pbar.data()), nullptr), "CVodeSetSensParams");
  const double f = options_.sensitivity_tolerance_factor;
  if (f == 1.0) {
    check_cvodes(CVodeSensEEtolerances(mem()), "CVodeSensEEtolerances");
  } else {
    std::vector<double> atolS(pbar.size());
    for (size_t j = 0; j < pbar.size(); ++j) atolS[j] = f * options_.atol / pbar[j];
    check_cvodes(CVodeSensSStolerances(mem(), f * options_.rtol, atolS.data()), "CVodeSensSStolerances");
  }
  check_cvodes(CVodeSetSensErrCon(mem(), options_.sensitivity_error_control ? SUNTRUE : SUNFALSE), "CVodeSetSensErrCon");
}

void CvodesSession::init_roots(const std::vector<int>& directions, CVRootFn g) {
  if (directions.empty()) return;
  std::vector<int> dirs = directions;  // CVodeSetRootDirection takes a non-const array
  check_cvodes(CVodeRootInit(mem(), static_cast<int>(dirs.size()), g), "CVodeRootInit");
  check_cvodes(CVodeSetRootDirection(mem(), dirs.data()), "CVodeSetRootDirection");
  CVodeSetNoInactiveRootWarn(mem());
}

void CvodesSession::root_info(int* found) { check_cvodes(CVodeGetRootInfo(mem(), found), "CVodeGetRootInfo"); }

int CvodesSession::interpolation_degree() {
  int q = 0;
  CVodeGetLastOrder(mem(), &q);
  return q;
}

double CvodesSession::current_time() {
  double t = 0.0;
  CVodeGetCurrentTime(mem(), &t);
  return t;
}

double CvodesSession::last_step() {
  double h = 0.0;
  CVodeGetLastStep(mem(), &h);
  return h;
}

void CvodesSession::set_stop_time(double t) { check_cvodes(CVodeSetStopTime(mem(), t), "CVodeSetStopTime"); }

int CvodesSession::advance(double tout, double* t, int itask) { return CVode(mem(), tout, y(), t, itask); }

void CvodesSession::fetch_sensitivities() {
  double t = 0.0;
  check_cvodes(CVodeGetSens(mem(), &t, s()), "CVodeGetSens");
}

void CvodesSession::set_state_atol(const std::vector<double>& atol) {
  const OwnedVector v = vector_like(y(), atol);
  check_cvodes(CVodeSVtolerances(mem(), options_.rtol, v.get()), "CVodeSVtolerances");
}

void CvodesSession::restart(double t) {
  before_restarts_ = stats();
  check_cvodes(CVodeReInit(mem(), t, y()), "CVodeReInit");
  if (ns_ > 0) {
    const int method = options_.sensitivity_method == SensitivityMethod::Staggered ? CV_STAGGERED : CV_SIMULTANEOUS;
    check_cvodes(CVodeSensReInit(mem(), method, s()), "CVodeSensReInit");
  }
}


long CvodesSession::total_steps() const {
  long v = 0;
  CVodeGetNumSteps(mem(), &v);
  return before_restarts_.steps + v;
}

SolverStats CvodesSession::stats() const {
  using Getter = int (*)(void*, long*);
  const std::pair<Getter, long SolverStats::*> counters[] = {
      {CVodeGetNumSteps, &SolverStats::steps},
      {CVodeGetNumErrTestFails, &SolverStats::error_test_failures},
      {CVodeGetNumNonlinSolvIters, &SolverStats::newton_iterations},
      {CVodeGetNumNonlinSolvConvFails, &SolverStats::newton_failures},
      {CVodeGetNumLinSolvSetups, &SolverStats::linear_setups},
      {CVodeGetNumRhsEvals, &SolverStats::rhs_evals},
      {CVodeGetNumJacEvals, &SolverStats::jac_evals}};
  SolverStats since_restart;
  for (const auto& [get, field] : counters) get(mem(), &(since_restart.*field));
  SolverStats total = before_restarts_;
  add_counters(total, since_restart);
  return total;
}

}  // namespace phasmid::solver
