// Periodic-orbit continuation against closed forms and published values
// (docs/continuation.md): the Stuart-Landau oscillator (period, nontrivial multiplier
// exp(-2 lambda T), the Hopf point at lambda = 0; its subcritical form's fold at lambda = -1/4),
// the van der Pol oscillator's period against mu, and the relay oscillator whose switches at
// events make the monodromy carry saltation terms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include <Eigen/Dense>

#include "common/error.hpp"
#include "config/config.hpp"
#include "continuation/continuation.hpp"
#include "model/ode_model.hpp"

using namespace phasmid;
using namespace phasmid::continuation;

namespace {

std::unique_ptr<model::OdeModel> make(const std::string& type, const std::string& keys = "") {
  return config::build_model(config::parse_config("[model]\ntype = \"" + type + "\"\n" + keys, "test"));
}

ShootingOptions tight(solver::RootSpec section, double transient, double max_period) {
  ShootingOptions o;
  o.section = section;
  o.transient_ms = transient;
  o.max_period_ms = max_period;
  o.solver.rtol = o.solver.atol = 1e-11;
  o.tolerance = 1e-9;
  return o;
}

ContinuationOptions along(const std::string& parameter, double start, double end, double initial_step,
                          double max_step, const ShootingOptions& shooting) {
  ContinuationOptions o;
  o.parameter = parameter;
  o.start = start;
  o.end = end;
  o.initial_step = initial_step;
  o.max_step = max_step;
  o.shooting = shooting;
  return o;
}

const SpecialPoint* find_kind(const Branch& b, const std::string& kind) {
  for (const auto& s : b.special)
    if (s.kind == kind) return &s;
  return nullptr;
}

double nontrivial(const BranchPoint& b) {
  for (size_t i = 0; i < b.multipliers.size(); ++i)
    if (i != b.trivial) return b.multipliers[i].real();
  return NAN;
}

// ---- Stuart-Landau ------------------------------------------------------------------------
// Section: y rising through 0 (theta = 0). omega = 2 pi / 100 rad/ms: T = 100 ms.
ContinuationOptions sl_options(double start, double end) {
  ContinuationOptions o = along("sl.lambda", start, end, 0.005, 0.01, tight({1, 0.0, +1}, 1500, 150));
  o.min_step = 1e-6;
  o.max_points = 200;
  o.shooting.residual_rtol = 1e-13;
  return o;
}

TEST(Continuation, StuartLandauPeriodMultiplierAndHopfPoint) {
  auto m = make("stuart_landau");
  const Branch b = continue_cycles(*m, m->parameters().values(), sl_options(0.05, -0.01));
  ASSERT_GE(b.points.size(), 5u);
  const double T = 100.0;
  for (const auto& p : b.points) {
    EXPECT_NEAR(p.period_ms, T, 1e-6) << "lambda " << p.parameter;
    EXPECT_NEAR(nontrivial(p), std::exp(-2.0 * p.parameter * T), 1e-6) << "lambda " << p.parameter;
    EXPECT_NEAR(p.multipliers[p.trivial].real(), 1.0, 1e-6);
    EXPECT_NEAR(p.y0[0], std::sqrt(p.parameter), 1e-7);  // on the circle r = sqrt(lambda) at theta = 0
    EXPECT_TRUE(p.stable);
  }
  EXPECT_NEAR(b.points.front().parameter, 0.05, 1e-12);
  ASSERT_FALSE(b.special.empty());
  EXPECT_EQ(b.special.back().kind, "hopf");
  EXPECT_NEAR(b.special.back().parameter, 0.0, 1e-5);
  EXPECT_NEAR(b.special.back().period_ms, T, 1e-4);
}

// dr/dt = lambda r + r^3 - r^5: cycles at r^2 = (1 +- sqrt(1 + 4 lambda)) / 2, meeting at the
// fold lambda = -1/4; nontrivial multiplier exp(T (lambda + 3 r^2 - 5 r^4)). T = 10 ms keeps the
// unstable cycles' multipliers moderate (single shooting amplifies integration errors by them).
TEST(Continuation, SubcriticalStuartLandauPassesTheFoldOfCycles) {
  auto m = make("stuart_landau");
  std::vector<double> p = m->parameters().values();
  p[m->parameters().index("sl.c3")] = 1.0;
  p[m->parameters().index("sl.c5")] = -1.0;
  p[m->parameters().index("sl.x0")] = 1.0;
  p[m->parameters().index("sl.omega")] = 2 * M_PI / 10.0;
  ContinuationOptions o = sl_options(0.1, -0.5);
  o.initial_step = 0.02;
  o.max_step = 0.04;
  const Branch b = continue_cycles(*m, p, o);
  const SpecialPoint* fold = find_kind(b, "fold");
  ASSERT_NE(fold, nullptr);
  EXPECT_NEAR(fold->parameter, -0.25, 1e-5);
  EXPECT_NEAR(fold->period_ms, 10.0, 1e-6);
  size_t unstable = 0;
  for (const auto& q : b.points) {
    const double r2 = q.y0[0] * q.y0[0];
    const double root = std::sqrt(1.0 + 4.0 * q.parameter);
    const bool upper = r2 > 0.5;
    EXPECT_NEAR(r2, upper ? (1 + root) / 2 : (1 - root) / 2, 1e-6) << "lambda " << q.parameter;
    const double mu = std::exp(10.0 * (q.parameter + 3 * r2 - 5 * r2 * r2));
    EXPECT_NEAR(nontrivial(q), mu, 1e-6 * std::max(1.0, mu)) << "lambda " << q.parameter;
    EXPECT_EQ(q.stable, upper) << "lambda " << q.parameter;
    unstable += !q.stable;
  }
  EXPECT_GE(unstable, 3u);  // the branch went on past the fold onto the unstable cycles
  EXPECT_EQ(b.special.back().kind, "hopf");  // which shrink to the equilibrium at lambda = 0
  EXPECT_NEAR(b.special.back().parameter, 0.0, 1e-4);
}

// The transverse focus of the `transverse` Stuart-Landau kind: the complex pair
// exp(a T) exp(+-i beta T) (beta T = 1.3 rad) crosses the unit circle at a = 0, a torus.
TEST(Continuation, TorusBifurcationLocatedWhereTheComplexPairCrossesTheUnitCircle) {
  auto m = make("stuart_landau", "transverse = true\n");
  std::vector<double> p = m->parameters().values();
  p[m->parameters().index("sl.lambda")] = 0.05;
  const Branch b = continue_cycles(*m, p, along("sl.a", -0.0035, 0.003, 0.002, 0.002, tight({1, 0.0, +1}, 1500, 150)));
  const SpecialPoint* torus = find_kind(b, "torus");
  ASSERT_NE(torus, nullptr);
  EXPECT_NEAR(torus->parameter, 0.0, 1e-7);
  EXPECT_NEAR(torus->period_ms, 100.0, 1e-6);
  EXPECT_EQ(find_kind(b, "fold"), nullptr);
  EXPECT_EQ(find_kind(b, "period_doubling"), nullptr);
  for (const auto& q : b.points) {
    std::complex<double> pair(NAN, NAN);
    for (const auto& mu : q.multipliers)
      if (mu.imag() > 0) pair = mu;
    EXPECT_NEAR(std::abs(pair), std::exp(q.parameter * 100.0), 1e-6) << "a " << q.parameter;
    EXPECT_NEAR(std::arg(pair), 1.3, 1e-6) << "a " << q.parameter;
    EXPECT_EQ(q.stable, q.parameter < 0) << "a " << q.parameter;
  }
}

// ---- a family of cycles: two uncoupled Stuart-Landau oscillators ---------------------------
// A point of the uncoupled Stuart-Landau pair's branch in lambda (T = 100 ms): the trivial and
// one neutral multiplier at 1, the two radial ones exp(-2 lambda T), stable, the second
// oscillator on its circle sqrt(lambda) at the transient's relative phase 1 rad (within
// phase_tolerance).
static void expect_pair_point(const BranchPoint& q, double phase_tolerance) {
  const double T = 100.0, mu = std::exp(-2.0 * q.parameter * T);
  ASSERT_EQ(q.multipliers.size(), 4u);
  ASSERT_EQ(q.neutral.size(), 1u) << "lambda " << q.parameter;
  EXPECT_NEAR(q.multipliers[q.trivial].real(), 1.0, 1e-6);
  EXPECT_NEAR(q.multipliers[q.neutral[0]].real(), 1.0, 1e-6);
  for (size_t i = 0; i < 4; ++i)
    if (q.counted(i)) EXPECT_NEAR(q.multipliers[i].real(), mu, 1e-6) << "lambda " << q.parameter;
  EXPECT_TRUE(q.stable) << "lambda " << q.parameter;
  EXPECT_NEAR(q.period_ms, T, 1e-6);
  EXPECT_NEAR(std::hypot(q.y0[2], q.y0[3]), std::sqrt(q.parameter), 1e-7);
  EXPECT_NEAR(std::atan2(q.y0[3], q.y0[2]), 1.0, phase_tolerance) << "lambda " << q.parameter;
}

// pair = true, k = 0: every relative phase gives a cycle, so besides the trivial multiplier a
// second one is exactly 1, and the radial ones are exp(-2 lambda T) twice. With
// neutral_tolerance the predictor and the corrector take minimum-norm steps and keep the relative
// phase the transient left (the initial phase2 = 1 rad), the second 1 is neutral (not unstable, no branch
// point), and the branch runs to its end with the closed-form radius and multipliers.
TEST(Continuation, NeutralDirectionOfAFamilyOfCyclesIsKeptAndNotCounted) {
  auto m = make("stuart_landau", "pair = true\n");
  ContinuationOptions o = sl_options(0.05, 0.01);
  o.shooting.neutral_tolerance = 1e-4;
  const Branch b = continue_cycles(*m, m->parameters().values(), o);
  ASSERT_GE(b.points.size(), 4u);
  ASSERT_EQ(b.special.size(), 1u);
  EXPECT_EQ(b.special.back().kind, "range_end");
  // Kept to the isotropy of the arclength weights of x2 and y2 (their ranges over the sampled
  // first cycle); a step in the family's direction would move it by O(0.1) rad per point.
  for (const auto& q : b.points) expect_pair_point(q, 1e-4);
  EXPECT_NEAR(b.points.back().parameter, 0.01, 1e-12);
}

// With the second oscillator's phase held instead (y2 rising through 0, one held phase for the
// one neutral direction), the family's member is fixed by a condition: the measured fraction is
// the closed form (2 pi - 1) / (2 pi) (theta2 = theta1 + 1 rad, y2 = 0 rising at theta2 = 2 pi),
// the relative phase stays 1 rad to Newton's precision (1e-8, against 1e-4 for the
// minimum-norm steps above), and the second 1 is still neutral, not a loss of stability.
TEST(Continuation, HeldPhasePinsTheMemberOfAFamilyOfCycles) {
  auto m = make("stuart_landau", "pair = true\n");
  ContinuationOptions o = sl_options(0.05, 0.01);
  o.shooting.neutral_tolerance = 1e-4;
  o.shooting.held_phases = {{"y2 rising", {3, 0.0, +1}}};
  const Branch b = continue_cycles(*m, m->parameters().values(), o);
  ASSERT_GE(b.points.size(), 4u);
  ASSERT_EQ(b.special.size(), 1u);
  EXPECT_EQ(b.special.back().kind, "range_end");
  ASSERT_EQ(b.held_phases.size(), 1u);
  EXPECT_NEAR(b.held_phases[0].fraction, (2 * M_PI - 1) / (2 * M_PI), 1e-7);
  for (const auto& q : b.points) expect_pair_point(q, 1e-8);
  EXPECT_NEAR(b.points.back().parameter, 0.01, 1e-12);
}

// The held phase's row of Newton's matrix (d y_s(fraction T) / d(y0, T, lambda) from the
// sensitivities at the held time) against central differences of the plain runs' held
// residual, on the coupled pair (k = 0.01 /ms) continued in lambda together with sl.omega.
TEST(Continuation, HeldPhaseRowMatchesFiniteDifferences) {
  auto m = make("stuart_landau", "pair = true\n");
  std::vector<double> p = m->parameters().values();
  p[m->parameters().index("sl.k")] = 0.01;
  ParameterPath path;
  path.index = {m->parameters().index("sl.lambda"), m->parameters().index("sl.omega")};
  path.base = {0.05, p[path.index[1]]};
  path.slope = {1.0, 0.3};
  path.start = 0.05;
  ShootingOptions o = tight({1, 0.0, +1}, 0, 150);
  o.held_phases = {{"x2 falling", {2, 0.1, -1}, 0.3}};
  const Cycle c{{0.2, 0.0, 0.05, 0.21}, 97.0, 0.06, 0.0};
  const Shot s = shoot(*m, p, path, c, o.solver, o.held_phases);
  ASSERT_EQ(s.held_rows.rows(), 1);
  EXPECT_NEAR(s.held_residual[0], shooting_residual(*m, p, path, c, o)[4], 1e-9);
  auto held = [&](Cycle x) { return shooting_residual(*m, p, path, x, o)[4]; };
  const double h = 1e-5;
  for (size_t j = 0; j < 6; ++j) {
    Cycle a = c, b = c;
    if (j < 4) a.y0[j] += h, b.y0[j] -= h;
    else if (j == 4) a.period_ms += h, b.period_ms -= h;
    else a.parameter += h, b.parameter -= h;
    const double fd = (held(a) - held(b)) / (2 * h);
    EXPECT_NEAR(s.held_rows(0, j), fd, 1e-6 * std::max(1.0, std::abs(fd))) << "column " << j;
  }
}

// The coupled pair (k = 0.01 /ms) settles in phase; its antisymmetric perturbations decay k
// faster on both sides: multipliers 1, exp(-2 k T), exp(-2 lambda T), exp(-2 (lambda + k) T).
TEST(Continuation, CoupledStuartLandauPairMultipliersInClosedForm) {
  auto m = make("stuart_landau", "pair = true\n");
  std::vector<double> p = m->parameters().values();
  p[m->parameters().index("sl.lambda")] = 0.05;
  p[m->parameters().index("sl.k")] = 0.01;
  NewtonReport rep;
  Shot shot;
  const Cycle c = find_cycle(*m, p, tight({1, 0.0, +1}, 1500, 150), rep, &shot);
  ASSERT_TRUE(rep.converged);
  const double T = 100.0, lambda = 0.05, k = 0.01;
  EXPECT_NEAR(c.period_ms, T, 1e-6);
  EXPECT_NEAR(c.y0[2], c.y0[0], 1e-7);
  EXPECT_NEAR(c.y0[3], c.y0[1], 1e-7);
  const auto mu = multipliers(shot.monodromy);
  ASSERT_EQ(mu.size(), 4u);
  const double expected[] = {1.0, std::exp(-2 * k * T), std::exp(-2 * lambda * T), std::exp(-2 * (lambda + k) * T)};
  for (size_t i = 0; i < 4; ++i) EXPECT_NEAR(mu[i].real(), expected[i], 1e-6) << "multiplier " << i;
  EXPECT_EQ(multiplier_roles(mu, 1e-4).neutral.size(), 0u);
}

// The minimum-norm step leaves a direction of near-zero singular value alone: J = Q diag(2, 1,
// 0.5, 1e-10) Q^T with Q = H/2 (H the 4x4 Hadamard matrix); the QR step divides F's component
// along the last direction by 1e-10, the step with one neutral direction drops it and solves the
// rest exactly.
TEST(Continuation, NewtonStepDropsNearZeroSingularDirections) {
  Eigen::Matrix4d Q;
  Q << 1, 1, 1, 1, 1, -1, 1, -1, 1, 1, -1, -1, 1, -1, -1, 1;
  Q /= 2.0;
  const Eigen::MatrixXd J = Q * Eigen::Vector4d(2.0, 1.0, 0.5, 1e-10).asDiagonal() * Q.transpose();
  const Eigen::VectorXd F = Q * Eigen::Vector4d(0.4, -0.3, 0.1, 1e-6);
  const Eigen::VectorXd full = newton_step(J, F, 0), min_norm = newton_step(J, F, 1);
  EXPECT_NEAR(Q.col(3).dot(full), -1e4, 1.0);
  EXPECT_NEAR(Q.col(3).dot(min_norm), 0.0, 1e-9);
  EXPECT_NEAR(Q.col(0).dot(min_norm), -0.2, 1e-12);
  EXPECT_NEAR(Q.col(1).dot(min_norm), 0.3, 1e-12);
  EXPECT_NEAR(Q.col(2).dot(min_norm), -0.2, 1e-12);
}

// ---- van der Pol ----------------------------------------------------------------------------
// Periods of x'' - mu (1 - x^2) x' + x = 0. T(1) = 6.6632868593 (the published value:
// Hairer, Norsett & Wanner, Solving Ordinary Differential Equations I, 2nd ed., Springer 1993,
// Sect. I.16, Exercise 1: period 6.6632868593231301896996820305 of the cycle through y' = 0,
// y = 2.00861986087484313650940188), asserted to 1e-6. T(2) = 7.6299 and T(5) = 11.6122 are
// our own (Newton shooting at rtol 1e-11: 7.62987, 11.61223); no published table of them was
// found to cite. Section: x' falling through 0.
TEST(Continuation, VanDerPolPeriodAgainstMu) {
  auto m = make("van_der_pol");
  const ContinuationOptions o = along("vdp.mu", 1.0, 5.0, 0.25, 0.5, tight({1, 0.0, -1}, 200, 40));
  const Branch b = continue_cycles(*m, m->parameters().values(), o);
  ASSERT_EQ(b.special.back().kind, "range_end");
  EXPECT_NEAR(b.points.front().period_ms, 6.6632868593, 1e-6);
  EXPECT_NEAR(b.points.back().parameter, 5.0, 1e-12);
  EXPECT_NEAR(b.points.back().period_ms, 11.6122, 5e-5);
  for (size_t k = 1; k < b.points.size(); ++k) {
    EXPECT_GT(b.points[k].period_ms, b.points[k - 1].period_ms);
    EXPECT_TRUE(b.points[k].stable);
  }
  std::vector<double> p = m->parameters().values();
  p[m->parameters().index("vdp.mu")] = 2.0;
  NewtonReport rep;
  const Cycle c2 = find_cycle(*m, p, o.shooting, rep);
  EXPECT_TRUE(rep.converged);
  EXPECT_NEAR(c2.period_ms, 7.6299, 5e-5);
  EXPECT_LT(rep.residual, 1e-8);
}

// ---- relay oscillator (saltation) ---------------------------------------------------------
// T = 2 tau ln((1+a)/(1-a)); multipliers 1 and exp(-k T) (closed form in
// src/scenario/kinds/relay_oscillator.cpp); without the saltation terms the first would be
// exp(-T/tau) = ((1-a)/(1+a))^2. Section: x rising through 0.
TEST(Continuation, RelayOscillatorMultipliersCarryTheSaltationTerms) {
  auto m = make("relay_oscillator");
  const ContinuationOptions o = along("relay.a", 0.3, 0.7, 0.05, 0.1, tight({0, 0.0, +1}, 300, 100));
  const Branch b = continue_cycles(*m, m->parameters().values(), o);
  ASSERT_GE(b.points.size(), 4u);
  EXPECT_EQ(b.special.back().kind, "range_end");
  const double tau = 10.0, k = 0.05;
  for (const auto& q : b.points) {
    const double a = q.parameter, T = 2 * tau * std::log((1 + a) / (1 - a));
    EXPECT_NEAR(q.period_ms, T, 1e-6) << "a " << a;
    ASSERT_EQ(q.multipliers.size(), 2u);
    EXPECT_NEAR(q.multipliers[q.trivial].real(), 1.0, 1e-6) << "a " << a;
    EXPECT_NEAR(nontrivial(q), std::exp(-k * T), 1e-6) << "a " << a;
    EXPECT_TRUE(q.stable);
  }
}

// ---- relay oscillator with a flip ----------------------------------------------------------
// flip = true: (p, q) turned by pi while u = +1, p grown by exp(alpha T/2) and q shrunk by
// exp(-beta T/2) while u = -1 (closed form in src/scenario/kinds/relay_oscillator.cpp):
// multipliers 1, exp(-k T), -exp(alpha T/2), -exp(-beta T/2); the third passes through -1 at
// alpha = 0, a period doubling. T = 2 tau ln 3 at a = 0.5.
TEST(Continuation, RelayFlipPeriodDoublingAtAlphaZero) {
  auto m = make("relay_oscillator", "flip = true\n");
  const ContinuationOptions o = along("relay.alpha", -0.02, 0.02, 0.005, 0.01, tight({0, 0.0, +1}, 300, 100));
  const Branch b = continue_cycles(*m, m->parameters().values(), o);
  ASSERT_GE(b.points.size(), 5u);
  EXPECT_EQ(b.special.back().kind, "range_end");
  const double tau = 10.0, k = 0.05, beta = 0.05, T = 2 * tau * std::log(3.0);
  for (const auto& q : b.points) {
    const double alpha = q.parameter;
    EXPECT_NEAR(q.period_ms, T, 1e-6) << "alpha " << alpha;
    ASSERT_EQ(q.multipliers.size(), 4u);
    EXPECT_NEAR(q.multipliers[q.trivial].real(), 1.0, 1e-6) << "alpha " << alpha;
    for (double expected : {std::exp(-k * T), -std::exp(alpha * T / 2), -std::exp(-beta * T / 2)}) {
      double best = INFINITY;
      for (size_t i = 0; i < q.multipliers.size(); ++i)
        if (i != q.trivial) best = std::min(best, std::abs(q.multipliers[i] - expected));
      EXPECT_LT(best, 1e-6) << "alpha " << alpha << ", multiplier " << expected;
    }
    EXPECT_EQ(q.stable, alpha < 0) << "alpha " << alpha;
  }
  const SpecialPoint* pd = find_kind(b, "period_doubling");
  ASSERT_NE(pd, nullptr);
  EXPECT_NEAR(pd->parameter, 0.0, 1e-7);
  EXPECT_NEAR(pd->period_ms, T, 1e-6);
  EXPECT_EQ(find_kind(b, "fold"), nullptr);
  EXPECT_EQ(find_kind(b, "torus"), nullptr);
}

}  // namespace

// A converged cycle's state lies on the section only up to round-off; a run from a state one
// ulp before a root's level finds that root within round-off of t = 0, and CVODES stops at its
// next step ("root found at and very near" the start: CV_ILL_INPUT), as the three-leg
// continuation did at its lift-off section. on_section and aligned_roots put the state and the
// root exactly on the level, where CVODES ignores a zero at the start.
TEST(Continuation, CycleRunStartingOneUlpBeforeASectionRoot) {
  auto m = make("relay_oscillator");  // x rises from -a towards +1 under u = +1 at the start
  const solver::RootSpec section{0, 0.4, +1};
  const std::vector<double> y0 = {std::nextafter(section.level, -1.0), 0.0};
  const solver::RootSpec root{0, std::nextafter(section.level, 1.0), 0};  // the feature's own rounding
  solver::SolverOptions so;
  so.rtol = so.atol = 1e-6;
  const std::vector<double> p = m->parameters().values();
  {
    CycleModel cm(*m, y0, 0.0);
    EXPECT_THROW(solver::Simulator(cm, so).run(cm.extend(p), {0.0, 30.0}, {{0, section.level, 0}}), Error);
  }
  CycleModel cm(*m, on_section(y0, section), 0.0);
  const auto roots = aligned_roots({root}, section);
  EXPECT_EQ(roots[0].level, section.level);
  const solver::SolveResult r = solver::Simulator(cm, so).run(cm.extend(p), {0.0, 30.0}, roots);
  // x = 1 - 0.6 exp(-t/10) reaches the switch at +0.5 after 10 ln(6/5) ms; the first root after
  // the start is x falling back through 0.4 under u = -1.
  ASSERT_FALSE(r.events.empty());
  EXPECT_GT(r.events[0].t, 1.0);
  EXPECT_EQ(r.events[0].direction, -1);
}
