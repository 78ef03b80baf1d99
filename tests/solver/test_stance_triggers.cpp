// Triggers with a stance condition ([[triggers]] in_stance, model::CommandTrigger::in_stance):
// an event counts only if every listed leg is in stance at that moment (beta below its
// <leg>.coupling.beta_thr_pr, the touched-down side of its touch-down threshold). Three legs
// with rate motoneurons, 3 s: the triggered command times are put beyond the end of the run
// (delay_ms), so the triggered run is the plain run, and each resolved time minus the delay is
// checked against the crossing that qualifies in the plain run's event list.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "../model_config_error.hpp"
#include "common/error.hpp"
#include "config/config.hpp"
#include "features/features.hpp"

using namespace phasmid;

namespace {
constexpr double kEndMs = 3000;
constexpr double kDelayMs = 10000;  // command time = event + 10 s: beyond the run, which it leaves unchanged
constexpr double kDebounceMs = 40;  // the triggers' default

std::string head(const std::string& gait) {
  return "[model]\ntype = \"three_legs\"\ngait = \"" + gait + "\"\nmotoneuron = \"rate\"\n";
}
// One system for both runs (a plain run would otherwise be integrated by joint networks, a
// triggered one never is), so that the events of the two runs agree.
const char* kSimulation = "[simulation]\nrtol = 1e-6\natol = 1e-6\n[simulation.expert]\npartitioning = \"whole\"\n";

struct LegsRun {
  std::unique_ptr<model::OdeModel> m;
  solver::SolveResult r;
  std::vector<solver::RootSpec> roots;
};

LegsRun run(const std::string& text) {
  auto cfg = config::parse_config(text, "stance.toml");
  LegsRun x;
  x.m = config::build_model(cfg);
  solver::Simulator sim(*x.m, config::simulation_settings(cfg).solver);
  x.roots = features::feature_roots(*x.m);
  x.r = sim.run(x.m->parameters().values(), solver::output_grid(kEndMs, 5.0), x.roots);
  return x;
}

// A leg's ground-contact crossings (time, direction: -1 touch-down, +1 lift-off) in a run, and
// whether it is in stance at t = 0.
struct LegEvents {
  std::vector<std::pair<double, int>> crossings;
  bool stance_at_start = false;
  // In stance at t: the last crossing before t was a touch-down (the state at the root is on
  // the touched-down side of the threshold after a touch-down, until the next lift-off).
  bool in_stance(double t) const {
    bool s = stance_at_start;
    for (const auto& [tc, dir] : crossings)
      if (tc < t) s = dir < 0;
    return s;
  }
  // Time to the nearest crossing (a condition evaluated this close to one would be ambiguous).
  double distance(double t) const {
    double d = INFINITY;
    for (const auto& c : crossings) d = std::min(d, std::abs(c.first - t));
    return d;
  }
};

LegEvents leg_events(const LegsRun& x, const std::string& leg) {
  const size_t beta = x.m->state_index(leg + ".ctr.beta");
  const double thr = x.m->parameters().value(leg + ".coupling.beta_thr_pr") * M_PI / 180.0;
  size_t root = x.roots.size();
  for (size_t i = 0; i < x.roots.size(); ++i)
    if (x.roots[i].state == beta && std::abs(x.roots[i].level - thr) < 1e-12) root = i;
  EXPECT_LT(root, x.roots.size()) << "no ground-contact root for " << leg;
  LegEvents out;
  for (const auto& e : x.r.events)
    if (e.root == root) out.crossings.push_back({e.t, e.direction});
  out.stance_at_start = x.r.state(0, beta) < thr;
  return out;
}

// The trigger's candidate events: crossings in `direction` from after_ms on, each at least the
// debounce time after the previous crossing of the same threshold (either direction).
std::vector<double> candidates(const LegEvents& ev, int direction, double after_ms) {
  std::vector<double> out;
  double previous = -INFINITY;
  for (const auto& [t, dir] : ev.crossings) {
    if (dir == direction && t - previous >= kDebounceMs && t >= after_ms) out.push_back(t);
    previous = t;
  }
  return out;
}

// The occurrence-th candidate at which all `legs` are in stance (NaN: none in the run).
double qualifying(const std::vector<double>& cands, const std::vector<const LegEvents*>& legs, int occurrence = 1) {
  int n = 0;
  for (double t : cands) {
    bool ok = true;
    for (const LegEvents* l : legs) {
      EXPECT_GT(l->distance(t), 1e-3) << "a condition leg crosses its threshold at the candidate " << t;
      ok = ok && l->in_stance(t);
    }
    if (ok && ++n == occurrence) return t;
  }
  return NAN;
}

double resolved_event(const LegsRun& x, const std::string& name) {
  for (const auto& c : x.r.commands)
    if (x.m->parameters().at(c.parameter).name == name) return c.t_ms - kDelayMs;
  return NAN;
}

void print(const std::string& leg, const LegEvents& ev) {
  std::printf("%-6s (stance at 0: %d):", leg.c_str(), ev.stance_at_start);
  for (const auto& [t, dir] : ev.crossings) std::printf(" %s%.1f", dir < 0 ? "v" : "^", t);
  std::printf("\n");
}

// One trigger: its command time, event (<leg>.touchdown or <leg>.liftoff) and condition.
struct Spec {
  std::string set, leg, kind;
  std::vector<std::string> in_stance;
  double after_ms = 0;
  int occurrence = 1;
  // What the plain run's events must show for the case to test what it is meant to: the
  // condition excludes no candidate up to the qualifying one, or it excludes some (the trigger
  // fires later than without it), or every candidate in the run.
  enum { kSame, kLater, kNever } outcome;
};

std::string toml_of(const Spec& s) {
  std::string legs;
  for (const auto& l : s.in_stance) legs += (legs.empty() ? "\"" : ", \"") + l + "\"";
  char buf[512];
  std::snprintf(buf, sizeof buf, "[[triggers]]\nset = \"%s\"\nevent = \"%s.%s\"\nafter_ms = %g\ndelay_ms = %g\noccurrence = %d\n",
                s.set.c_str(), s.leg.c_str(), s.kind.c_str(), s.after_ms, kDelayMs, s.occurrence);
  return buf + (s.in_stance.empty() ? std::string() : "in_stance = [" + legs + "]\n");
}

// Runs the gait without and with the triggers (whose command times lie beyond the run) and
// checks each trigger's event time against the crossing that qualifies in the plain run.
void check(const std::string& gait, const std::vector<Spec>& specs) {
  std::string triggers;
  for (const Spec& s : specs) triggers += toml_of(s);
  LegsRun plain = run(head(gait) + kSimulation);
  LegsRun trig = run(head(gait) + triggers + kSimulation);
  ASSERT_TRUE(plain.r.commands.empty());
  ASSERT_EQ(trig.m->triggers().size(), specs.size());
  std::map<std::string, LegEvents> ev;
  for (const char* leg : {"front", "middle", "hind"}) {
    ev[leg] = leg_events(plain, leg);
    print(leg, ev[leg]);
    // The triggers do not change the run: the same crossings (one system, as a triggered run).
    LegEvents b = leg_events(trig, leg);
    ASSERT_EQ(ev[leg].crossings.size(), b.crossings.size()) << leg;
    for (size_t i = 0; i < b.crossings.size(); ++i)
      ASSERT_NEAR(ev[leg].crossings[i].first, b.crossings[i].first, 1e-9) << leg << " crossing " << i;
  }
  for (const Spec& s : specs) {
    const std::vector<double> cands = candidates(ev[s.leg], s.kind == "touchdown" ? -1 : +1, s.after_ms);
    std::vector<const LegEvents*> cond;
    for (const auto& l : s.in_stance) cond.push_back(&ev[l]);
    const double expected = qualifying(cands, cond, s.occurrence);
    const double unconditional = qualifying(cands, {}, s.occurrence);
    const double got = resolved_event(trig, s.set);
    std::printf("%s.%s, %zu legs in stance, after %g ms, occurrence %d: qualifying %.4f ms (without the condition %.4f), "
                "trigger %.4f ms\n",
                s.leg.c_str(), s.kind.c_str(), s.in_stance.size(), s.after_ms, s.occurrence, expected, unconditional, got);
    ASSERT_FALSE(std::isnan(unconditional)) << s.set << ": no candidate event in the run";
    switch (s.outcome) {  // the case is what it is meant to be (else the run changed: choose other events)
      case Spec::kSame: ASSERT_EQ(expected, unconditional) << s.set; break;
      case Spec::kLater: ASSERT_GT(expected, unconditional) << s.set << ": the condition does not exclude the first candidate"; break;
      case Spec::kNever: ASSERT_TRUE(std::isnan(expected)) << s.set << ": a candidate qualifies"; break;
    }
    if (std::isnan(expected))
      EXPECT_TRUE(std::isnan(got)) << s.set << ": no event qualifies in the run, but the trigger fired at " << got;
    else
      EXPECT_NEAR(got, expected, 1e-6) << s.set;
  }
}
}  // namespace

// Tripod: front and hind legs step together (the hind leg touches down first), the middle leg
// in antiphase. The configs' tripod -> tetrapod switch: the front's touch-down with the hind
// leg in stance, found at its first touch-down; the hind's touch-down with the front leg in
// stance never happens (the front is still in swing); occurrence counts qualifying events.
TEST(StanceTriggers, TripodFrontAndHindLegs) {
  check("tripod", {{"gait.switch_ms", "front", "touchdown", {"hind"}, 2000, 1, Spec::kSame},
                   {"front.command.ld_hold_ms", "front", "touchdown", {}, 2000, 1, Spec::kSame},
                   {"hind.command.ld_hold_ms", "hind", "touchdown", {"front"}, 1000, 1, Spec::kNever},
                   {"middle.command.ld_hold_ms", "front", "touchdown", {"hind"}, 1500, 2, Spec::kSame},
                   {"middle.command.ld_release2_ms", "front", "liftoff", {"middle"}, 0, 1, Spec::kNever}});
}

// Tetrapod (hind -> middle -> front): the condition skips candidates until the other leg is
// down, or leaves none in the run; the n-th occurrence is the n-th qualifying event.
TEST(StanceTriggers, TetrapodConditionExcludesTheFirstCandidates) {
  check("tetrapod", {{"gait.switch_ms", "hind", "touchdown", {"front"}, 1000, 1, Spec::kLater},
                     {"hind.command.ld_hold_ms", "hind", "touchdown", {}, 1000, 1, Spec::kSame},
                     {"front.command.ld_hold_ms", "front", "liftoff", {"hind"}, 1000, 1, Spec::kLater},
                     {"middle.command.ld_hold_ms", "front", "touchdown", {"middle", "hind"}, 0, 1, Spec::kNever},
                     {"front.command.ld_release2_ms", "front", "touchdown", {"middle"}, 0, 1, Spec::kSame},
                     // occurrence counts the qualifying events only
                     {"middle.command.ld_release2_ms", "hind", "touchdown", {"front"}, 0, 2, Spec::kLater}});
}

// Malformed in_stance: one-line errors naming file:line.
TEST(StanceTriggers, ConfigErrors) {
  const std::string head3 = head("tripod") + "[[triggers]]\nset = \"gait.switch_ms\"\nevent = \"front.touchdown\"\n";
  auto error_of = [&](const std::string& extra) { return test::model_config_error(head3 + extra); };
  auto expect = [&](const std::string& extra, const std::string& want) {
    const std::string e = error_of(extra);
    EXPECT_EQ(e.rfind(want, 0), 0u) << "got: " << e << "\nwant: " << want;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  };
  expect("in_stance = [\"hnd\"]\n", "bad.toml:8: unknown leg 'hnd' in [[triggers]] 'in_stance' (expected one of front, middle, hind)");
  expect("in_stance = [\"hind\",\n  \"L2\"]\n", "bad.toml:9: unknown leg 'L2' in [[triggers]] 'in_stance'");
  expect("in_stance = \"hind\"\n", "bad.toml:8: 'in_stance' must be an array of leg names");
  expect("in_stance = [\"hind\", 3]\n", "bad.toml:8: 'in_stance' must be an array of leg names");
  expect("in_stance = []\n", "bad.toml:8: 'in_stance' names no leg");
  expect("in_stance = [\"front\"]\n", "bad.toml:8: leg 'front' in 'in_stance' is the leg of the event front.touchdown");
  expect("in_stance = [\"hind\", \"hind\"]\n", "bad.toml:8: leg 'hind' is named twice in 'in_stance'");
  expect("in_stnce = [\"hind\"]\n", "bad.toml:8: unknown key 'in_stnce' in [[triggers]]");
  EXPECT_EQ(error_of("in_stance = [\"hind\", \"middle\"]\n"), "no error");
  // A single-leg model has no other leg to name.
  const std::string leg = "[model]\ntype = \"leg\"\nleg = \"middle\"\ndirection_switch = true\n[[triggers]]\n"
                          "set = \"middle.command.backward_ms\"\nevent = \"middle.touchdown\"\nin_stance = [\"hind\"]\n";
  try {
    config::build_model(config::parse_config(leg, "leg.toml"));
    ADD_FAILURE() << "in_stance naming a leg the model does not have accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "leg.toml:8: unknown leg 'hind' in [[triggers]] 'in_stance' (expected one of middle)");
  }
}
