#pragma once
// Periodic orbits of an OdeModel by Newton shooting on a Poincare section
// (docs/continuation.md). A cycle is (y0, T): y0 on the section g(y0) = y0[s] - level = 0, and
// the state one period T after y0 equals y0. Newton's matrix is the monodromy matrix
// Phi = dy(T)/dy0 from the Floquet machinery (sensitivity::InitialValueModel: forward
// sensitivities with respect to shifts of the initial state), bordered by f(y(T)) (the
// derivative with respect to T), the section's row and, for continuation, dy(T)/dlambda.
// A model that switches at events (model triggers) keeps its triggers in the cycle's run, so
// Phi carries the saltation terms the solver applies at each switch (docs/sensitivity.md).
//
// Contract: a cycle run starts at the model time t0 of the section crossing found after the
// transient, so that central commands at fixed times (a levator hold released at 1.5 s) are in
// the state they have there; the cycle must not depend on t0 beyond that (no command inside
// a cycle). A model with triggers starts every cycle at t0 = 0 with no triggered command
// fired: its discrete mode at the section must be its mode at t = 0.
#include <cmath>
#include <complex>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sensitivity/floquet.hpp"
#include "solver/simulator.hpp"

namespace phasmid::continuation {

// The model started at y0 at model time t0 (its run's time 0), with the base model's declared
// structure (gait features) and, where t0 = 0, its triggers (switches at events).
class CycleModel : public sensitivity::InitialValueModel {
 public:
  CycleModel(const model::OdeModel& base, std::vector<double> y0, double t0);
};

// The parameters a continuation moves with lambda: p[index[j]] = base[j] + slope[j] (lambda -
// start); the continuation parameter itself has slope 1, linked parameters follow it.
struct ParameterPath {
  std::vector<size_t> index;
  std::vector<double> base, slope;
  double start = 0.0;
  void apply(std::vector<double>& p, double lambda) const {
    for (size_t j = 0; j < index.size(); ++j) p[index[j]] = base[j] + slope[j] * (lambda - start);
  }
};

// A held phase: the cycle's state y[event.state] passes event.level at t = fraction * T after
// the section. For a cycle of a family (legs whose relative phases nothing pulls back), one
// held phase per neutral direction turns the family's member into an isolated solution: the
// held phases replace the minimum-norm steps, and the member is the one with the same timing
// of these events within the cycle (e.g. each leg's lift-off as a fraction of the step).
struct HeldPhase {
  std::string name;        // as configured (e.g. "front.liftoff"), for output
  solver::RootSpec event;  // its direction picks the crossing whose fraction is measured
  double fraction = NAN;   // in (0, 1); NaN: measured on the first cycle (measure_fractions)
};

struct ShootingOptions {
  solver::RootSpec section{0, 0.0, +1};  // the cycle starts where y[state] crosses level in direction
  double transient_ms = 5000.0;   // integrated before the first section crossing is taken
  double max_period_ms = 2000.0;  // search window for the first period after the transient
  double tolerance = 1e-7;        // converged when max_i |y_i(T) - y0_i| < tolerance * growth (state units)
  int max_iterations = 12;
  solver::SolverOptions solver;   // the runs with sensitivities (monodromy)
  // Relative tolerance of the plain runs that evaluate the residual y(T) - y0 (atol scaled
  // alike); 0: solver.rtol. A plain run costs 1/(n + 1) of one with the monodromy, so it can
  // afford a tolerance that puts the residual's integration noise below `tolerance`.
  double residual_rtol = 0.0;
  // Neutral directions: a cycle that belongs to a family (legs whose relative phases nothing
  // pulls back, two uncoupled oscillators) has further multipliers at 1 besides the trivial
  // one, and Newton's matrix is singular in them up to integration error, so a full Newton
  // step divides noise by a near-zero singular value. With neutral_tolerance > 0 the
  // multipliers within it of 1 beyond the trivial one are neutral: the corrector and the
  // tangent take minimum-norm steps with that many smallest singular values dropped (they move
  // to the nearest member of the family, measured in `scale`), and the branch leaves them out
  // of the stability and special-point tests. 0: every direction is solved (rank-revealing QR).
  double neutral_tolerance = 0.0;
  // Held phases (see HeldPhase): with them the Newton system has n + 2 + held rows (cycle,
  // section, held phases, the last row) for the n + 2 unknowns and is solved in the least-squares
  // sense, consistent at a member of the family; no direction is dropped. neutral_tolerance
  // still says which multipliers are left out of the stability tests.
  std::vector<HeldPhase> held_phases;
  // Typical size of each unknown of z = (y0, T, lambda) for the minimum-norm steps (the
  // continuation sets its arclength scaling W^-1); empty: 1 for each.
  Eigen::VectorXd scale;
  // Called at each corrector iteration with its index, the residual max |y(T) - y0| (and of
  // the held phases), the row where it is largest (NewtonReport::worst_row) and whether the monodromy was computed at that point (the verb's --trace); may be empty.
  std::function<void(int, double, size_t, bool)> on_iteration;
};

struct Cycle {
  std::vector<double> y0;  // state on the section
  double period_ms = 0.0;
  double parameter = 0.0;  // the continuation parameter's value (unused without one)
  double t0 = 0.0;         // model time at the section (CycleModel)
};

// The shooting residual at a guess and its derivatives.
struct Shot {
  Eigen::VectorXd residual;   // y(T) - y0
  Eigen::MatrixXd monodromy;  // dy(T)/dy0
  Eigen::VectorXd f_end;      // f(y(T)) = dy(T)/dT
  Eigen::VectorXd dy_dparam;  // dy(T)/dlambda (size 0 without a parameter)
  // Per held phase j: y[s_j](fraction_j T) - level_j and its derivative by z = (y0, T, lambda)
  // (held x (n + 2); the lambda column zero without a parameter).
  Eigen::VectorXd held_residual;
  Eigen::MatrixXd held_rows;
  double max_residual() const { return residual.size() ? residual.cwiseAbs().maxCoeff() : 0.0; }
};

// One integration of the cycle's run over [0, T] with sensitivities to y0 and to the path's
// parameters at lambda = cycle.parameter (none: an empty path). Throws Error on integration failure.
Shot shoot(const model::OdeModel& model, std::vector<double> p, const ParameterPath& path, const Cycle& cycle,
           const solver::SolverOptions& solver, const std::vector<HeldPhase>& held = {});

struct NewtonReport {
  int iterations = 0;
  double residual = 0.0;  // max |y(T) - y0| at the returned cycle
  size_t worst_row = 0;   // where it is largest: a state index, or n + 1 + j for held phase j
  bool converged = false;
  long shots = 0, plain_shots = 0;  // integrations with sensitivities / without
};

// y(T) - y0, followed by the held phases' residuals (Shot::held_residual), by one plain
// integration (no sensitivities) at ShootingOptions::residual_rtol.
Eigen::VectorXd shooting_residual(const model::OdeModel& model, std::vector<double> p, const ParameterPath& path,
                                  const Cycle& cycle, const ShootingOptions& options);

// The corrector on z = (y0, T, lambda): y(T; y0, lambda) - y0 = 0, y0[s] = level, the held
// phases and row . (z - z_pred) = 0 (row = e_lambda: lambda fixed). Quasi-Newton: the monodromy is
// computed at the start (one run with sensitivities; with `start`, a linearisation at a nearby
// z such as the previous point of a branch, Newton's matrix starts from it instead), the iteration continues with Broyden's
// rank-one updates of Newton's matrix and plain runs for the residual; a step that raises the
// residual is halved (up to four times), and the monodromy is recomputed where the residual
// falls by less than half or halving fails; two such steps in a row with a fresh monodromy end
// the iteration unconverged (the guess lies outside the linearisation's reach). At the converged z one more run with sensitivities
// gives `shot` (monodromy, f, dy/dlambda: the multipliers), its residual the plain run's.
// `report` counts the runs (also when an integration fails: then Error is thrown).
struct Correction {
  Eigen::VectorXd z;
  Shot shot;
};
Correction correct_cycle(const model::OdeModel& model, const std::vector<double>& p, const ParameterPath& path,
                         double t0, Eigen::VectorXd z, const Eigen::VectorXd& z_pred, const Eigen::VectorXd& row,
                         const ShootingOptions& options, NewtonReport& report, const Shot* start = nullptr);

// The Newton step dz solving J dz = -F (least squares where J has more rows than columns):
// rank-revealing QR where neutral = 0 and J is square; else in the variables z / col_scale with
// the rows multiplied by row_scale (empty: ones), by QR where neutral = 0 and otherwise as the
// minimum-norm step with the `neutral` smallest singular values dropped
// (ShootingOptions::neutral_tolerance).
Eigen::VectorXd newton_step(const Eigen::MatrixXd& J, const Eigen::VectorXd& F, size_t neutral,
                            const Eigen::VectorXd& col_scale = {}, const Eigen::VectorXd& row_scale = {});

// 1 / typical size of each row of Newton's matrix, from ShootingOptions::scale: a cycle row by
// its state's scale, the section row and each held phase's row by their state's, the last row
// as it is. Empty where the options have no scale.
Eigen::VectorXd row_scale(const ShootingOptions& options);

// The fraction of the period at which each held phase's event first occurs in its direction on
// the cycle (run over one period). Throws Error naming the held phase if it has no crossing.
std::vector<double> measure_fractions(const model::OdeModel& model, std::vector<double> p,
                                      const ParameterPath& path, const Cycle& cycle, const ShootingOptions& options);

// Which multipliers (by decreasing modulus, as multipliers() gives them) play which part: the
// one nearest 1 is the trivial one (the cycle's phase direction); the further ones within
// neutral_tolerance of 1 are neutral (none where it is 0).
struct MultiplierRoles {
  size_t trivial = 0;
  std::vector<size_t> neutral;
};
MultiplierRoles multiplier_roles(const std::vector<std::complex<double>>& mu, double neutral_tolerance);

// Newton's matrix [Phi - I, f(y(T)), dy/dlambda; e_section; held rows; row] (a zero lambda
// column without a parameter).
Eigen::MatrixXd newton_matrix(const Shot& shot, size_t section_state, const Eigen::VectorXd& row);

// The state with its section component set exactly to the section's level, and roots on the
// section's state at its level (within round-off) given exactly that level: a run from a state
// a rounding error before a root's level finds the root within round-off of t = 0 and CVODES
// stops ("root found at and very near" the start: CV_ILL_INPUT).
std::vector<double> on_section(std::vector<double> y0, const solver::RootSpec& section);
std::vector<solver::RootSpec> aligned_roots(std::vector<solver::RootSpec> roots, const solver::RootSpec& section);

// The name of row i of the cycle equations (NewtonReport::worst_row): its state's, or
// "held phase <name>".
std::string row_name(const model::OdeModel& model, const ShootingOptions& options, size_t i);

// Newton on (y0, T) at fixed parameters, from `guess`; `shot` (if given) receives the
// linearisation at the returned cycle.
Cycle newton_fixed_parameter(const model::OdeModel& model, const std::vector<double>& p, const Cycle& guess,
                             const ShootingOptions& options, NewtonReport& report, Shot* shot = nullptr);

// Integrates past the transient, takes the last full period between two section crossings as
// the guess (sensitivity::find_periodic_orbit) and refines it by Newton, without the held
// phases (the cycle it finds gives their fractions: measure_fractions). Throws Error if the
// run has no two crossings after the transient or Newton does not converge.
Cycle find_cycle(const model::OdeModel& model, const std::vector<double>& p, const ShootingOptions& options,
                 NewtonReport& report, Shot* shot = nullptr);

// max(1, largest |multiplier|) of multipliers by decreasing modulus: how much an integration
// error at the start of a cycle can grow by its end, the factor on ShootingOptions::tolerance.
double growth(const std::vector<std::complex<double>>& mu);

// Floquet multipliers (eigenvalues of the monodromy) by decreasing modulus.
std::vector<std::complex<double>> multipliers(const Eigen::MatrixXd& monodromy);

}  // namespace phasmid::continuation
