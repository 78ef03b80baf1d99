#include "continuation/continuation.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <optional>

#include "common/error.hpp"
#include "features/features.hpp"

namespace phasmid::continuation {
namespace {
using Vec = Eigen::VectorXd;

// The continuation's fixed inputs and counters. z = (y0, T, lambda) has n + 2 entries.
struct Context {
  const model::OdeModel& model;
  std::vector<double> p;
  ParameterPath path;
  double t0 = 0.0;  // model time of the cycles' section crossing
  size_t n = 0;
  const ContinuationOptions& o;
  Vec w;  // arclength weights (W)
  ShootingOptions shooting;  // o.shooting with scale = W^-1 (the minimum-norm steps' measure)
  long shots = 0, plain_shots = 0;
  bool integration_failed = false;
  // A solution crossing the section slower than this (in its direction) is refused: Newton
  // may converge to an equilibrium on the section (any T, f = 0) once the cycle is gone.
  double min_rate = 0.0;
  NewtonReport last_failure;  // of the last corrector that did not converge
};

struct Solved {
  Vec z;
  Shot shot;
  std::vector<std::complex<double>> multipliers;  // of shot.monodromy, by decreasing modulus
  int iterations = 0;
};

Eigen::MatrixXd jacobian(const Context& c, const Shot& s, const Vec& row) {
  return newton_matrix(s, c.o.shooting.section.state, row);
}

// The corrector (continuation/shooting.hpp) from z with row . (z - z_pred) = 0.
// `start`: a linearisation near z (the previous point's) that Newton's matrix starts from.
std::optional<Solved> correct(Context& c, const Vec& z, const Vec& z_pred, const Vec& row, const Shot* start = nullptr) {
  const ShootingOptions& so = c.shooting;
  NewtonReport rep;
  Correction r;
  try {
    r = correct_cycle(c.model, c.p, c.path, c.t0, z, z_pred, row, so, rep, start);
  } catch (const Error&) {  // integration failure, tangential switch
    c.integration_failed = true;
  }
  c.shots += rep.shots;
  c.plain_shots += rep.plain_shots;
  if (!rep.converged) c.last_failure = rep;
  if (c.integration_failed || !rep.converged) return std::nullopt;
  const size_t sec = so.section.state;
  const double dir = so.section.direction == 0 ? 1.0 : so.section.direction;
  const double rate = so.section.direction == 0 ? std::abs(r.shot.f_end[sec]) : dir * r.shot.f_end[sec];
  if (!(rate > c.min_rate)) return std::nullopt;
  std::vector<std::complex<double>> mu = multipliers(r.shot.monodromy);
  return Solved{r.z, std::move(r.shot), std::move(mu), rep.iterations};
}

// Unit tangent of the branch in weighted coordinates, oriented along `dir` (weighted).
Vec tangent(const Context& c, const Solved& s, const Vec& dir) {
  const Vec row = dir.cwiseProduct(c.w);
  const Eigen::MatrixXd J = jacobian(c, s.shot, row);
  Vec e = Vec::Zero(J.rows());
  e[J.rows() - 1] = 1.0;
  // Minimum-norm where neutral directions are declared and not held: the tangent then has no
  // component in them. With held phases it keeps their fractions.
  const ShootingOptions& so = c.shooting;
  const size_t neutral =
      so.held_phases.empty() ? multiplier_roles(s.multipliers, so.neutral_tolerance).neutral.size() : 0;
  Vec t = -c.w.cwiseProduct(newton_step(J, e, neutral, so.scale, row_scale(so)));
  t.normalize();
  return t.dot(dir) < 0 ? Vec(-t) : t;
}

// The solved cycle at z_pred's arclength along weighted direction dir from `from`.
// `start` as for correct().
std::optional<Solved> step(Context& c, const Vec& from, const Vec& dir, double ds, const Shot* start = nullptr) {
  const Vec z_pred = from + ds * dir.cwiseQuotient(c.w);
  return correct(c, z_pred, z_pred, dir.cwiseProduct(c.w), start);
}

// Features and per-state ranges (max - min over one period) from feature_cycles periods of
// the converged cycle z.
struct CycleRun {
  std::vector<features::Feature> features;
  std::vector<double> ranges;
};

CycleRun run_cycle(const Context& c, const Vec& z) {
  const size_t n = c.n;
  std::vector<double> p = c.p;
  c.path.apply(p, z[n + 1]);
  const solver::RootSpec& section = c.o.shooting.section;
  CycleModel cm(c.model, on_section(std::vector<double>(z.data(), z.data() + n), section), c.t0);
  const std::vector<double> pe = cm.extend(p);
  const double T = z[n];
  std::vector<double> times;
  for (int k = 0; k <= 200; ++k) times.push_back(T * k / 200.0);
  times.push_back(c.o.feature_cycles * T);
  solver::SolverOptions so = c.o.shooting.solver;
  so.progress = false;
  const solver::SolveResult r = solver::Simulator(cm, so).run(pe, times, aligned_roots(features::feature_roots(cm, pe), section));
  CycleRun out;
  for (size_t i = 0; i < n; ++i) {
    double lo = INFINITY, hi = -INFINITY;
    for (size_t k = 0; k + 1 < r.t.size(); ++k) lo = std::min(lo, r.state(k, i)), hi = std::max(hi, r.state(k, i));
    out.ranges.push_back(hi - lo);
  }
  out.features = features::compute_features(cm, r, {});
  return out;
}

BranchPoint describe(const Context& c, const Solved& s, const Vec& t, const std::vector<std::string>& names) {
  BranchPoint b;
  const size_t n = c.n;
  b.y0.assign(s.z.data(), s.z.data() + n);
  b.period_ms = s.z[n];
  b.parameter = s.z[n + 1];
  b.newton_iterations = s.iterations;
  b.residual = s.shot.max_residual();
  b.tangent_parameter = t[n + 1] / c.w[n + 1];
  b.multipliers = s.multipliers;
  MultiplierRoles roles = multiplier_roles(b.multipliers, c.shooting.neutral_tolerance);
  b.trivial = roles.trivial;
  b.neutral = std::move(roles.neutral);
  b.stable = true;
  for (size_t i = 0; i < b.multipliers.size(); ++i)
    if (b.counted(i) && std::abs(b.multipliers[i]) >= 1.0) b.stable = false;
  const CycleRun run = run_cycle(c, s.z);
  double sum = 0.0;
  for (double r : run.ranges) sum += r * r;
  b.amplitude = std::sqrt(sum);
  b.features.assign(names.size(), NAN);
  for (size_t j = 0; j < names.size(); ++j)
    for (const auto& x : run.features)
      if (x.name == names[j]) b.features[j] = x.value;
  return b;
}

// ---- test functions of the special points ------------------------------------------------
bool is_real(std::complex<double> m) { return std::abs(m.imag()) <= 1e-12 * std::max(1.0, std::abs(m)); }

// The nontrivial multiplier nearest `target` among those `pick` accepts; NaN if none.
template <class Pick>
std::complex<double> nearest(const BranchPoint& b, std::complex<double> target, Pick pick) {
  std::complex<double> best(NAN, NAN);
  for (size_t i = 0; i < b.multipliers.size(); ++i) {
    const auto m = b.multipliers[i];
    if (!b.counted(i) || !pick(m)) continue;
    if (std::isnan(best.real()) || std::abs(m - target) < std::abs(best - target)) best = m;
  }
  return best;
}

struct TestFunction {
  std::string kind;
  double (*value)(const BranchPoint&);
};

double fold_test(const BranchPoint& b) { return b.tangent_parameter; }
double pd_test(const BranchPoint& b) { return nearest(b, -1.0, [](auto m) { return is_real(m) && m.real() < 0; }).real() + 1.0; }
double bp_test(const BranchPoint& b) { return nearest(b, 1.0, [](auto m) { return is_real(m) && m.real() > 0; }).real() - 1.0; }
double torus_test(const BranchPoint& b) {
  double best = NAN;
  for (size_t i = 0; i < b.multipliers.size(); ++i)
    if (b.counted(i) && !is_real(b.multipliers[i])) {
      const double d = std::abs(b.multipliers[i]) - 1.0;
      if (std::isnan(best) || std::abs(d) < std::abs(best)) best = d;
    }
  return best;
}

const TestFunction kTests[] = {{"fold", fold_test}, {"period_doubling", pd_test}, {"torus", torus_test}};

bool crosses(double a, double b) { return std::isfinite(a) && std::isfinite(b) && a * b < 0; }

// Secant (regula falsi, Illinois) on the arclength s in (0, sB) from point A along dir.
SpecialPoint locate(Context& c, const Vec& zA, const Vec& dir, double sB, double fA, double fB, const TestFunction& tf,
                    const std::vector<std::string>& names, size_t index) {
  double s0 = 0.0, s1 = sB, f0 = fA, f1 = fB;
  SpecialPoint sp{index, tf.kind, NAN, NAN, ""};
  int it = 0, kept = -1;
  for (; it < c.o.locate_iterations; ++it) {
    const double s = s0 - f0 * (s1 - s0) / (f1 - f0);
    auto solved = step(c, zA, dir, s);
    if (!solved) break;
    const BranchPoint b = describe(c, *solved, tangent(c, *solved, dir), names);
    const double f = tf.value(b);
    sp.parameter = b.parameter;
    sp.period_ms = b.period_ms;
    if (!std::isfinite(f) || std::abs(f) < 1e-12 || std::abs(s1 - s0) < 1e-12 * sB) break;
    // Illinois: the end kept twice in a row has its value halved, so that both ends move.
    const int end_kept = f * f0 < 0 ? 0 : 1;
    if (end_kept == 0) s1 = s, f1 = f;
    else s0 = s, f0 = f;
    if (end_kept == kept) (end_kept == 0 ? f0 : f1) /= 2;
    kept = end_kept;
  }
  sp.note = "located by " + std::to_string(it) + " secant iterations on the test function";
  return sp;
}

// Special points between consecutive points A and B.
void detect(Context& c, const BranchPoint& A, const BranchPoint& B, const Vec& zA, const Vec& zB,
            const std::vector<std::string>& names, size_t index, std::vector<SpecialPoint>& out) {
  const Vec d = c.w.cwiseProduct(zB - zA);
  const double sB = d.norm();
  const Vec dir = d / sB;
  for (const TestFunction& tf : kTests) {
    const double fA = tf.value(A), fB = tf.value(B);
    if (crosses(fA, fB)) out.push_back(locate(c, zA, dir, sB, fA, fB, tf, names, index));
  }
  if (crosses(bp_test(A), bp_test(B)) && !crosses(fold_test(A), fold_test(B)))
    out.push_back({index, "branch_point", B.parameter, B.period_ms, "a real multiplier crossed +1 without a fold"});
}

// ---- ends of the branch ---------------------------------------------------------------------
// Hopf-like end: amplitude^2 is linear in lambda near a Hopf point; extrapolate it to zero.
SpecialPoint hopf_end(const std::vector<BranchPoint>& pts, const std::string& why) {
  const BranchPoint& b = pts.back();
  SpecialPoint sp{pts.size() - 1, "hopf", b.parameter, b.period_ms, why};
  if (pts.size() < 2) return sp;
  const BranchPoint& a = pts[pts.size() - 2];
  const double a2 = a.amplitude * a.amplitude, b2 = b.amplitude * b.amplitude;
  if (a2 == b2 || b.parameter == a.parameter) return sp;
  sp.parameter = b.parameter - b2 * (b.parameter - a.parameter) / (b2 - a2);
  sp.period_ms = b.period_ms + (b.period_ms - a.period_ms) * (sp.parameter - b.parameter) / (b.parameter - a.parameter);
  sp.note = why + "; parameter and period extrapolated to zero amplitude";
  return sp;
}

// The branch runs up a vertical asymptote in (lambda, T): over the last three steps the
// period grows while the branch is nearly parallel to the period axis (|d lambda/ds| < 1e-2),
// as on the approach to a homoclinic orbit or a saddle-node on the cycle, where T ~ -ln|lambda - lambda_c|
// or |lambda - lambda_c|^(-1/2) would take ever smaller parameter steps to follow.
bool period_runs_away(const std::vector<BranchPoint>& pts) {
  if (pts.size() < 4) return false;
  for (size_t k = pts.size() - 3; k < pts.size(); ++k)
    if (!(pts[k].period_ms > pts[k - 1].period_ms) || !(std::abs(pts[k].tangent_parameter) < 1e-2)) return false;
  return true;
}

// How a branch ends where no step down to min_step converges.
SpecialPoint failure_end(const Context& c, const std::vector<BranchPoint>& pts, double amax, double t_first) {
  const BranchPoint& b = pts.back();
  const BranchPoint* a = pts.size() > 1 ? &pts[pts.size() - 2] : nullptr;
  if (c.integration_failed)
    return {pts.size() - 1, "integration_failure", b.parameter, b.period_ms, "the next cycle's integration failed"};
  if (a && b.amplitude < 0.5 * amax && b.amplitude < a->amplitude)
    return hopf_end(pts, "no cycle beyond; the amplitude was shrinking");
  if (a && b.period_ms > 2.0 * t_first && b.period_ms > a->period_ms)
    return {pts.size() - 1, "period_unbounded", b.parameter, b.period_ms, "no cycle beyond; the period was growing"};
  return {pts.size() - 1, "no_convergence", b.parameter, b.period_ms,
          "Newton shooting failed down to the minimum step; last residual " + std::to_string(c.last_failure.residual) +
              ", largest in " + row_name(c.model, c.shooting, c.last_failure.worst_row)};
}

}  // namespace

void fill_default_steps(ContinuationOptions& o) {
  const double range = std::abs(o.end - o.start);
  if (o.initial_step <= 0) o.initial_step = range / 50;
  if (o.min_step <= 0) o.min_step = range * 1e-5;
  if (o.max_step <= 0) o.max_step = range / 10;
}

namespace {

ContinuationOptions checked(const model::OdeModel& model, ContinuationOptions o) {
  const double range = std::abs(o.end - o.start);
  if (!(range > 0)) throw Error("[continuation] range must have two different values");
  fill_default_steps(o);
  if (!(o.min_step <= o.initial_step && o.initial_step <= o.max_step))
    throw Error("[continuation] needs min_step <= initial_step <= max_step");
  if (o.shooting.section.state >= model.num_states()) throw Error("[continuation] section state out of range");
  if (o.max_points < 2) throw Error("[continuation] max_points must be at least 2");
  return o;
}

// Weights: lambda in its unit, T relative to the first period, each state relative to its
// range over the first cycle (at least 1 % of the largest range), all across the parameter range.
Vec weights(const Context& c, const Vec& z0, const CycleRun& first) {
  const size_t n = c.n;
  const double range = std::abs(c.o.end - c.o.start);
  // A state that barely moves would otherwise weigh its integration noise into every step.
  const double floor = 1e-2 * *std::max_element(first.ranges.begin(), first.ranges.end());
  Vec w(n + 2);
  for (size_t i = 0; i < n; ++i)
    w[i] = range / (std::max({first.ranges[i], floor, 1e-300}) * std::sqrt(static_cast<double>(n)));
  w[n] = range / z0[n];
  w[n + 1] = 1.0;
  return w;
}

// The continuation parameter (slope 1) and the linked ones, at their values at lambda = start.
ParameterPath path_of(const model::OdeModel& model, const ContinuationOptions& o) {
  ParameterPath path;
  path.start = o.start;
  path.index = {model.parameters().index(o.parameter)};
  path.base = {o.start};
  path.slope = {1.0};
  for (const auto& l : o.linked) {
    path.index.push_back(model.parameters().index(l.name));
    path.base.push_back(l.from);
    path.slope.push_back((l.to - l.from) / (o.end - o.start));
  }
  return path;
}

}  // namespace

const std::vector<std::pair<std::string, std::string>>& special_point_kinds() {
  static const std::vector<std::pair<std::string, std::string>> k = {
      {"fold", "fold of cycles: the branch turns back in the parameter, a multiplier passes through +1"},
      {"period_doubling", "a real multiplier passes through -1: a cycle of twice the period branches off"},
      {"torus", "a complex pair of multipliers crosses the unit circle: a torus (quasi-periodic motion) branches off"},
      {"branch_point", "a real multiplier passes through +1 without a fold: another branch of cycles crosses"},
      {"hopf", "the cycle shrinks to an equilibrium (amplitude -> 0): the rhythm is lost at a Hopf point"},
      {"period_unbounded", "the period grows without bound (homoclinic or saddle-node on the cycle)"},
      {"integration_failure", "the next cycle could not be integrated"},
      {"no_convergence", "Newton shooting failed down to the minimum step"},
      {"range_end", "the branch reached the end of the parameter range"},
      {"max_points", "the branch reached max_points"}};
  return k;
}

namespace {

// The branch's header: parameter, unit, section, tracked features (default: every feature the
// first cycle gives) with their units.
Branch new_branch(const model::OdeModel& model, const ContinuationOptions& o, const CycleRun& first) {
  Branch br;
  br.parameter = o.parameter;
  br.parameter_unit = model.parameters().at(o.parameter).unit;
  br.section = o.shooting.section;
  br.feature_names = o.features;
  if (br.feature_names.empty())
    for (const auto& f : first.features) br.feature_names.push_back(f.name);
  const auto catalogue = features::feature_catalogue(model);
  for (const auto& name : br.feature_names) {
    std::string unit;
    for (const auto& f : catalogue)
      if (f.name == name) unit = f.unit;
    br.feature_units.push_back(unit);
  }
  return br;
}

// The cycle at lambda = bound, from the secant between `from` and the step that left the range.
std::optional<Solved> land_on(Context& c, const Vec& from, const Vec& beyond, double bound) {
  const size_t n = c.n;
  Vec zp = from + (bound - from[n + 1]) / (beyond[n + 1] - from[n + 1]) * (beyond - from);
  zp[n + 1] = bound;
  Vec row = Vec::Zero(n + 2);
  row[n + 1] = 1.0;
  return correct(c, zp, zp, row);
}

// An end the last point shows: the period running away, or the amplitude gone (Hopf-like).
std::optional<SpecialPoint> natural_end(const ContinuationOptions& o, const std::vector<BranchPoint>& pts, double amax,
                                        double t_first) {
  const BranchPoint& last = pts.back();
  if (last.period_ms > o.max_period_factor * t_first || period_runs_away(pts))
    return SpecialPoint{pts.size() - 1, "period_unbounded", last.parameter, last.period_ms,
                        "the period grows while the parameter stalls (or exceeds max_period_factor times the first)"};
  if (last.amplitude < o.hopf_amplitude_fraction * amax)
    return hopf_end(pts, "the amplitude fell below hopf_amplitude_fraction of the largest");
  return std::nullopt;
}

void count_runs(const Context& c, Branch& br, std::chrono::steady_clock::time_point t_start) {
  br.shots = c.shots;
  br.plain_shots = c.plain_shots;
  br.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
}

void report_point(const Context& c, Branch& br, std::chrono::steady_clock::time_point t_start) {
  if (!c.o.on_point) return;
  count_runs(c, br, t_start);
  c.o.on_point(br);
}

// The held phases' fractions not given are those of the first cycle.
void hold_phases_of(Context& c, const Cycle& first) {
  std::vector<HeldPhase>& held = c.shooting.held_phases;
  if (held.empty()) return;
  const std::vector<double> f =
      measure_fractions(c.model, c.p, c.path, {first.y0, first.period_ms, c.o.start, first.t0}, c.shooting);
  for (size_t j = 0; j < held.size(); ++j)
    if (std::isnan(held[j].fraction)) held[j].fraction = f[j];
}

}  // namespace

Branch continue_cycles(const model::OdeModel& model, std::vector<double> p, const ContinuationOptions& opt) {
  const auto t_start = std::chrono::steady_clock::now();
  const ContinuationOptions o = checked(model, opt);
  const size_t n = model.num_states();
  Context c{model, p, path_of(model, o), 0.0, n, o, Vec::Ones(n + 2), o.shooting, 0, 0, false, 0.0, NewtonReport{}};
  c.path.apply(c.p, o.start);
  NewtonReport rep;
  const Cycle first = find_cycle(model, c.p, o.shooting, rep);
  c.t0 = first.t0;
  hold_phases_of(c, first);
  Vec z0(n + 2);
  for (size_t i = 0; i < n; ++i) z0[i] = first.y0[i];
  z0[n] = first.period_ms;
  z0[n + 1] = o.start;
  const CycleRun run0 = run_cycle(c, z0);
  c.w = weights(c, z0, run0);
  c.shooting.scale = c.w.cwiseInverse();  // minimum-norm steps measure as the arclength does
  Branch br = new_branch(model, o, run0);
  char note[160];
  std::snprintf(note, sizeof note, "cycle at the start after the transient: residual %.3g after %d Newton iterations",
                rep.residual, rep.iterations);
  br.start_note = note;
  br.held_phases = c.shooting.held_phases;
  Vec dir = Vec::Zero(n + 2);
  dir[n + 1] = o.end > o.start ? 1.0 : -1.0;
  auto cur = correct(c, z0, z0, dir.cwiseProduct(c.w));
  if (!cur) throw Error("the cycle found at " + o.parameter + " = " + std::to_string(o.start) + " did not converge with the parameter column");
  c.min_rate = 1e-3 * std::abs(cur->shot.f_end[o.shooting.section.state]);
  dir = tangent(c, *cur, dir);  // predictors follow the tangent
  br.points.push_back(describe(c, *cur, dir, br.feature_names));
  report_point(c, br, t_start);
  const double lo = std::min(o.start, o.end), hi = std::max(o.start, o.end);
  double ds = o.initial_step, amax = br.points[0].amplitude;
  while (true) {
    if (static_cast<int>(br.points.size()) >= o.max_points) {
      br.special.push_back({br.points.size() - 1, "max_points", br.points.back().parameter, br.points.back().period_ms, ""});
      break;
    }
    c.integration_failed = false;
    auto next = step(c, cur->z, dir, ds, &cur->shot);
    if (!next) {
      ds /= 2;
      if (ds >= o.min_step) continue;
      br.special.push_back(failure_end(c, br.points, amax, z0[n]));
      break;
    }
    const double lam = next->z[n + 1];
    const bool outside = lam < lo || lam > hi;
    if (outside) {
      std::optional<Solved> landed = land_on(c, cur->z, next->z, lam > hi ? hi : lo);
      if (!landed) {
        br.special.push_back({br.points.size() - 1, "range_end", lam, br.points.back().period_ms, "the last step left the range"});
        break;
      }
      next.swap(landed);
    }
    // The next predictor: the tangent at the new point, oriented along the secant (so that
    // the branch goes on through a fold, where the tangent's lambda component changes sign).
    const Vec new_dir = tangent(c, *next, c.w.cwiseProduct(next->z - cur->z).normalized());
    try {  // the features' run and the location of special points integrate again
      BranchPoint b = describe(c, *next, new_dir, br.feature_names);
      detect(c, br.points.back(), b, cur->z, next->z, br.feature_names, br.points.size(), br.special);
      br.points.push_back(std::move(b));
    } catch (const Error& e) {
      br.special.push_back({br.points.size() - 1, "integration_failure", br.points.back().parameter,
                            br.points.back().period_ms, std::string("describing the next cycle: ") + e.what()});
      break;
    }
    report_point(c, br, t_start);
    cur = std::move(next);
    dir = new_dir;
    const BranchPoint& last = br.points.back();
    if (outside) {
      br.special.push_back({br.points.size() - 1, "range_end", last.parameter, last.period_ms, ""});
      break;
    }
    if (cur->iterations <= 3) ds = std::min(ds * 1.5, o.max_step);
    else if (cur->iterations > 6) ds = std::max(ds * 0.6, o.min_step);
    amax = std::max(amax, last.amplitude);
    if (auto end = natural_end(o, br.points, amax, z0[n])) {
      br.special.push_back(*end);
      break;
    }
  }
  count_runs(c, br, t_start);
  return br;
}

}  // namespace phasmid::continuation
