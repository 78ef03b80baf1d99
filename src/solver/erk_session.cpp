#include "solver/erk_session.hpp"

#include <arkode/arkode.h>
#include <arkode/arkode_erkstep.h>
#include <nvector/nvector_serial.h>

#include <cstdlib>

#include "common/error.hpp"
#include "solver/dopri_session.hpp"

namespace phasmid::solver {

// The drivers compare advance()'s flags and pass itask with CVODES' names.
static_assert(ARK_SUCCESS == CV_SUCCESS && ARK_TSTOP_RETURN == CV_TSTOP_RETURN && ARK_ROOT_RETURN == CV_ROOT_RETURN);
static_assert(ARK_NORMAL == CV_NORMAL && ARK_ONE_STEP == CV_ONE_STEP);

namespace {

void check_arkode(int flag, const char* what) {
  if (flag < 0) throw SolverError(std::string("ARKODE setup failed in ") + what + " (flag " + std::to_string(flag) + ")");
}

ARKODE_ERKTableID table_of(IntegratorKind kind) {
  switch (kind) {
    case IntegratorKind::ErkBs3: return ARKODE_BOGACKI_SHAMPINE_4_2_3;
    case IntegratorKind::ErkDp5: return ARKODE_DORMAND_PRINCE_7_4_5;
    case IntegratorKind::ErkVerner65: return ARKODE_VERNER_8_5_6;
    case IntegratorKind::ErkFehlberg78: return ARKODE_FEHLBERG_13_7_8;
    default: throw Error("internal: ErkSession needs an explicit Runge-Kutta integrator kind");
  }
}

}  // namespace

std::unique_ptr<IntegratorSession> make_explicit_session(SUNContext ctx, const SolverOptions& options, const double* y0,
                                                         size_t n, CVRhsFn rhs, void* user_data) {
  if (options.integrator == IntegratorKind::Dopri5) return std::make_unique<DopriSession>(ctx, options, y0, n, rhs, user_data);
  return std::make_unique<ErkSession>(ctx, options, y0, n, rhs, user_data);
}

void ErkSession::FreeMemory::operator()(void* mem) const { ERKStepFree(&mem); }

ErkSession::ErkSession(SUNContext ctx, const SolverOptions& options, const double* y0, size_t n, CVRhsFn rhs,
                       void* user_data)
    : rhs_(rhs), user_data_(user_data), rtol_(options.rtol) {
  y_.reset(new_state_vector(ctx, options, y0, n));
  mem_.reset(ERKStepCreate(rhs_trampoline, 0.0, y(), ctx));
  if (!mem_) throw SolverError("ERKStepCreate failed");
  check_arkode(ERKStepSetErrHandlerFn(mem(), [](int, const char*, const char*, char*, void*) {}, nullptr), "silence");
  check_arkode(ERKStepSetTableNum(mem(), table_of(options.integrator)), "ERKStepSetTableNum");
  check_arkode(ERKStepSStolerances(mem(), options.rtol, options.atol), "ERKStepSStolerances");
  check_arkode(ERKStepSetUserData(mem(), this), "ERKStepSetUserData");
  check_arkode(ERKStepSetMaxNumSteps(mem(), options.max_steps), "ERKStepSetMaxNumSteps");
  // Cubic Hermite from the step's end values and slopes: no right-hand side beyond the stages
  // (degrees 4 and 5 cost one and two more per interpolated step).
  check_arkode(ERKStepSetInterpolantDegree(mem(), degree_), "ERKStepSetInterpolantDegree");
  // Spike flanks can reject a step several times in a row (ARKODE's default limit, 7, failed
  // Verner 6(5) on the single joint at rtol 1e-8).
  check_arkode(ERKStepSetMaxErrTestFails(mem(), 50), "ERKStepSetMaxErrTestFails");
  if (options.max_step_ms > 0) check_arkode(ERKStepSetMaxStep(mem(), options.max_step_ms), "ERKStepSetMaxStep");
}

ErkSession::~ErkSession() = default;

void ErkSession::init_roots(const std::vector<int>& directions, CVRootFn g) {
  if (directions.empty()) return;
  std::vector<int> dirs = directions;
  root_ = g;
  check_arkode(ERKStepRootInit(mem(), static_cast<int>(dirs.size()), root_trampoline), "ERKStepRootInit");
  check_arkode(ERKStepSetRootDirection(mem(), dirs.data()), "ERKStepSetRootDirection");
  ERKStepSetNoInactiveRootWarn(mem());
}

void ErkSession::set_stop_time(double t) { check_arkode(ERKStepSetStopTime(mem(), t), "ERKStepSetStopTime"); }

int ErkSession::advance(double tout, double* t, int itask) { return ERKStepEvolve(mem(), tout, y(), t, itask); }

// ERKStep (SUNDIALS 6.4) takes a recoverable right-hand-side failure (rhs returning 1 for a
// non-finite trial stage) as fatal, where CVODES retries a smaller step. Here such a stage
// returns huge finite slopes instead: the step's error estimate overflows, ERKStep rejects the
// step and retries it with at most a tenth of the step size, as CVODES would.
int ErkSession::rhs_trampoline(double t, N_Vector y, N_Vector ydot, void* self) {
  auto* s = static_cast<ErkSession*>(self);
  const int flag = s->rhs_(t, y, ydot, s->user_data_);
  if (flag <= 0) return flag;
  constexpr double kHuge = 1e150;
  double* f = N_VGetArrayPointer(ydot);
  for (sunindextype i = 0; i < N_VGetLength(ydot); ++i) f[i] = kHuge;
  return 0;
}

int ErkSession::root_trampoline(double t, N_Vector y, double* g, void* self) {
  auto* s = static_cast<ErkSession*>(self);
  return s->root_(t, y, g, s->user_data_);
}

void ErkSession::set_state_atol(const std::vector<double>& atol) {
  const OwnedVector v = vector_like(y(), atol);
  check_arkode(ERKStepSVtolerances(mem(), rtol_, v.get()), "ERKStepSVtolerances");
}

// ERKStepReset keeps the counters and options (tolerances, roots, table), forgets the step
// history and estimates a first step again, as CVodeReInit does.
void ErkSession::restart(double t) { check_arkode(ERKStepReset(mem(), t, y()), "ERKStepReset"); }

void ErkSession::root_info(int* found) { check_arkode(ERKStepGetRootInfo(mem(), found), "ERKStepGetRootInfo"); }

int ErkSession::dky(double t, int k, N_Vector out) { return ERKStepGetDky(mem(), t, k, out); }

double ErkSession::current_time() {
  double t = 0.0;
  ERKStepGetCurrentTime(mem(), &t);
  return t;
}

double ErkSession::last_step() {
  double h = 0.0;
  ERKStepGetLastStep(mem(), &h);
  return h;
}

std::string ErkSession::flag_name(int flag) const { return take_flag_name(ERKStepGetReturnFlagName(flag), flag); }

long ErkSession::total_steps() const {
  long v = 0;
  ERKStepGetNumSteps(mem(), &v);
  return v;
}

SolverStats ErkSession::stats() const {
  SolverStats s;
  ERKStepGetNumSteps(mem(), &s.steps);
  ERKStepGetNumRhsEvals(mem(), &s.rhs_evals);
  ERKStepGetNumErrTestFails(mem(), &s.error_test_failures);
  return s;
}

}  // namespace phasmid::solver
