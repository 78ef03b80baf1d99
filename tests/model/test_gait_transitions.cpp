// Knops 2013 Section 3.3 (Figs. 3.24-3.27): gait transitions both ways by central inhibition
// of the levator CPGs and reset, successively while the legs have ground contact
// (configs/gait_*.toml), with the command times triggered by touch-downs and lift-offs
// ([[triggers]]): tetrapod -> tripod from the hind leg's first lift-off after 5000 ms,
// tripod -> tetrapod from the front leg's first touch-down after 5000 ms (front and hind
// switched at their touch-down, the middle and front legs released one third and two thirds of
// the period after the hind leg's lift-off). Gait class from the lift-off phase lags before
// (2500-5000 ms) and after the transition; lift-offs from the located beta-threshold crossings,
// debounced as in features::compute_features. Also: the triggers reproduce the fixed command
// times read off the earlier runs, a transition requested two periods later completes too, and
// malformed triggers give a one-line error naming file:line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <vector>

#include "../model_config_error.hpp"
#include "common/error.hpp"
#include "config/config.hpp"
#include "features/features.hpp"
#include "build_info.hpp"

using namespace phasmid;

namespace {
struct GaitRun {
  std::unique_ptr<model::OdeModel> m;
  solver::SolveResult r;
  std::vector<solver::RootSpec> roots;

  // gait_class of the lift-offs in [t0, t1] (-1: not computable).
  double gait_class(double t0, double t1) const {
    solver::SolveResult w = r;
    w.events.erase(std::remove_if(w.events.begin(), w.events.end(), [&](const solver::Event& e) { return e.t > t1; }),
                   w.events.end());
    features::FeatureOptions fo;
    fo.discard_ms = t0;
    std::map<std::string, double> f;
    for (auto& x : features::compute_features(*m, w, fo)) f[x.name] = x.value;
    return f.count("gait_class") ? f["gait_class"] : -1.0;
  }

  // Lift-offs (beta rising through beta_thr_pr) of a leg after t0, with swing or stance
  // episodes shorter than 40 ms (ripples around the threshold) removed with their crossings.
  std::vector<double> liftoffs(const std::string& leg, double t0) const {
    const size_t beta = m->state_index(leg + ".ctr.beta");
    size_t root = roots.size();
    for (size_t k = m->angles().size(); k < roots.size(); ++k)
      if (roots[k].state == beta) { root = k; break; }
    EXPECT_LT(root, roots.size()) << leg;
    std::vector<const solver::Event*> ev;
    for (const auto& e : r.events)
      if (e.root == root && e.t >= t0) ev.push_back(&e);
    for (;;) {
      size_t kmin = ev.size();
      double dmin = 40.0;
      for (size_t k = 0; k + 1 < ev.size(); ++k) {
        if (ev[k]->direction == ev[k + 1]->direction) { kmin = k; dmin = -1; break; }
        if (ev[k + 1]->t - ev[k]->t < dmin) { dmin = ev[k + 1]->t - ev[k]->t; kmin = k; }
      }
      if (kmin == ev.size()) break;
      if (dmin < 0) ev.erase(ev.begin() + kmin + 1);
      else ev.erase(ev.begin() + kmin, ev.begin() + kmin + 2);
    }
    std::vector<double> lo;
    for (const auto* e : ev)
      if (e->direction > 0) lo.push_back(e->t);
    return lo;
  }
};

// `replace`: text substitutions in the config (e.g. a later after_ms); `sets`: --set overrides
// (fixed command times replace the triggers of those parameters).
GaitRun run(const std::string& config, const std::vector<std::string>& sets = {},
            const std::vector<std::pair<std::string, std::string>>& replace = {}, double t_end_ms = 8500) {
  auto cfg = config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/" + config);
  std::string text = cfg.text;
  for (const auto& [from, to] : replace) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  if (!replace.empty()) cfg = config::parse_config(text, cfg.path);
  GaitRun x;
  x.m = config::build_model(cfg, sets);
  auto s = config::simulation_settings(cfg);
  solver::Simulator sim(*x.m, s.solver);
  x.roots = features::feature_roots(*x.m);
  x.r = sim.run(x.m->parameters().values(), solver::output_grid(t_end_ms, 5.0), x.roots);
  return x;
}

// The value a trigger gave to a command time in the run (NaN: not triggered).
double resolved(const GaitRun& x, const std::string& name) {
  for (const auto& c : x.r.commands)
    if (x.m->parameters().at(c.parameter).name == name) return c.t_ms;
  return NAN;
}

// Triggered vs hand-read command times, and the lift-offs of the two runs (ms).
constexpr double kTriggeredVsFixedMs = 10;
constexpr double kLiftoffAgreementMs = 8;

// The fixed command times of the configs before [[triggers]], read off earlier runs.
const std::vector<std::string> kFixedTetrapodToTripod = {
    "gait.switch_ms=5050", "middle.command.ld_hold_ms=5070", "middle.command.ld_release2_ms=5280",
    "front.command.ld_hold_ms=5255", "front.command.ld_release2_ms=5500"};
const std::vector<std::string> kFixedTripodToTetrapod = {
    "gait.switch_ms=5120", "front.command.ld_hold_ms=5120", "front.command.ld_release2_ms=5625",
    "middle.command.ld_hold_ms=5120", "middle.command.ld_release2_ms=5457"};

// Each hind cycle from the first lift-off at or after t0 contains one middle and one front
// lift-off at the tetrapod lags (hind -> middle, hind -> front); returns the number of cycles.
int expect_tetrapod_cycles(const GaitRun& x, double t0, double lag_middle, double lag_front, double tol) {
  auto hind = x.liftoffs("hind", t0), middle = x.liftoffs("middle", t0), front = x.liftoffs("front", t0);
  int cycles = 0;
  for (size_t i = 0; i + 1 < hind.size(); ++i) {
    const double T = hind[i + 1] - hind[i];
    EXPECT_NEAR(T, 506, 5) << "hind cycle from " << hind[i];
    std::vector<double> m, f;
    for (double t : middle)
      if (t >= hind[i] && t < hind[i + 1]) m.push_back(t);
    for (double t : front)
      if (t >= hind[i] && t < hind[i + 1]) f.push_back(t);
    EXPECT_EQ(m.size(), 1u) << "hind cycle from " << hind[i];
    EXPECT_EQ(f.size(), 1u) << "hind cycle from " << hind[i];
    if (m.size() != 1 || f.size() != 1) continue;
    std::printf("lift-offs (ms): hind %.0f, middle %.0f, front %.0f; T %.0f ms; lags %.3f, %.3f\n", hind[i], m[0], f[0],
                T, (m[0] - hind[i]) / T, (f[0] - hind[i]) / T);
    EXPECT_NEAR((m[0] - hind[i]) / T, lag_middle, tol) << "hind cycle from " << hind[i];
    EXPECT_NEAR((f[0] - hind[i]) / T, lag_front, tol) << "hind cycle from " << hind[i];
    ++cycles;
  }
  return cycles;
}
}  // namespace

TEST(GaitTransitions, TetrapodToTripod) {
  GaitRun x = run("gait_tetrapod_to_tripod.toml");
  EXPECT_EQ(x.gait_class(2500, 5000), 1.0);  // tetrapod
  EXPECT_EQ(x.gait_class(6900, 8500), 2.0);  // tripod
  EXPECT_EQ(x.gait_class(5600, 8500), 2.0);  // successively, within one cycle: tripod from 5600 ms (Fig. 3.25)
  for (const char* leg : {"hind", "middle", "front"}) {  // the lift-offs docs/walking_model.md quotes
    std::printf("%s lift-offs (ms):", leg);
    for (double t : x.liftoffs(leg, 5000)) std::printf(" %.0f", t);
    std::printf("\n");
  }
}

TEST(GaitTransitions, TripodToTetrapod) {
  GaitRun x = run("gait_tripod_to_tetrapod.toml");
  EXPECT_EQ(x.gait_class(2500, 5000), 2.0);  // tripod
  EXPECT_EQ(x.gait_class(6900, 8500), 1.0);  // tetrapod
  // Successively, within one cycle (Figs. 3.26/3.27): tetrapod from the hind leg's first
  // lift-off after the switch (the front touch-down at 5116 ms) on.
  EXPECT_EQ(x.gait_class(5250, 8500), 1.0);

  // One leg after the other: the hind leg (not held) lifts off at the end of its stance
  // (5288 ms), the middle leg after its release at 5456 ms (5479 ms), the front leg after its
  // release at 5625 ms (5650 ms). The front leg stays in stance through its 505 ms hold
  // (before the levator motoneuron was silenced it lifted off after ~320 ms, at 5446 ms).
  const double t_switch = 5150;  // after the switch and the middle leg's forced touch-down
  auto hind = x.liftoffs("hind", t_switch), middle = x.liftoffs("middle", t_switch),
       front = x.liftoffs("front", t_switch);
  ASSERT_GE(hind.size(), 6u);
  ASSERT_GE(middle.size(), 6u);
  ASSERT_GE(front.size(), 6u);
  EXPECT_NEAR(hind[0], 5288, 10);
  EXPECT_NEAR(middle[0], 5481, 10);
  EXPECT_NEAR(front[0], 5651, 10);

  // From then on each hind cycle contains one middle and one front lift-off with the lags of
  // the tetrapod (measured 0.38-0.39 and 0.715-0.737; ideal 1/3, 2/3; the tetrapod started by
  // release times, three_legs_tetrapod.toml, has 0.363 and 0.713).
  // (The measured cycles are printed; docs/walking_model.md quotes them.)
  EXPECT_GE(expect_tetrapod_cycles(x, t_switch, 0.39, 0.73, 0.03), 5);
}

// (a) The triggers find the times that were read off earlier runs by hand (within 10 ms), and
// the runs agree: the same lift-offs after the switch, each leg's shifted by the shift of its
// own release. One exception: tetrapod -> tripod releases the middle leg at the hind leg's
// touch-down, as the text says (5252 ms), 28 ms before the hand-read 5280 ms; the middle leg
// then lifts off 28 ms earlier in every cycle, i.e. closer to antiphase (lag 0.50 instead of
// 0.56 of the hind cycle, docs/walking_model.md).
TEST(GaitTransitions, TriggersReproduceFixedTimes) {
  struct Case {
    const char* config;
    const std::vector<std::string>* fixed;
    std::string exception;  // command time whose trigger differs from the hand-read time
    double exception_ms;    // by this much (triggered - fixed)
  };
  for (const Case& c : {Case{"gait_tetrapod_to_tripod.toml", &kFixedTetrapodToTripod, "middle.command.ld_release2_ms", -28},
                        Case{"gait_tripod_to_tetrapod.toml", &kFixedTripodToTetrapod, "", 0}}) {
    SCOPED_TRACE(c.config);
    GaitRun trig = run(c.config), fixed = run(c.config, *c.fixed);
    EXPECT_TRUE(fixed.r.commands.empty());  // --set replaced every trigger
    std::map<std::string, double> shift_ms;  // triggered - fixed
    for (const std::string& s : *c.fixed) {
      const auto [name, value] = model::parse_assignment(s);
      shift_ms[name] = resolved(trig, name) - value;
      EXPECT_NEAR(shift_ms[name], name == c.exception ? c.exception_ms : 0.0, kTriggeredVsFixedMs) << name;
    }
    for (const std::string leg : {"hind", "middle", "front"}) {
      const std::string release = leg + ".command.ld_release2_ms";
      const double shift = shift_ms.count(release) ? shift_ms[release] : 0.0;
      auto a = trig.liftoffs(leg, 5000), b = fixed.liftoffs(leg, 5000);
      ASSERT_GE(a.size(), 5u) << leg;
      ASSERT_EQ(a.size(), b.size()) << leg;
      for (size_t i = 0; i < a.size(); ++i)
        EXPECT_NEAR(a[i] - b[i], shift, kLiftoffAgreementMs) << leg << " lift-off " << i;
    }
  }
}

// (b) A transition requested two cycles later (after_ms 5000 -> 5900) completes the same way:
// the triggers move with it, which fixed times read off one run cannot do.
TEST(GaitTransitions, LaterRequestCompletes) {
  {
    GaitRun x = run("gait_tripod_to_tetrapod.toml", {}, {{"after_ms = 5000", "after_ms = 5900"}}, 9500);
    const double t_switch = resolved(x, "gait.switch_ms");
    EXPECT_NEAR(t_switch, 5117 + 2 * 442, 15);  // the front's touch-down two tripod cycles later
    std::printf("tripod -> tetrapod requested after 5900 ms: switch at %.0f ms\n", t_switch);
    EXPECT_EQ(x.gait_class(2500, 5900), 2.0);   // tripod until the request
    EXPECT_EQ(x.gait_class(t_switch + 130, 9500), 1.0);
    EXPECT_GE(expect_tetrapod_cycles(x, t_switch + 30, 0.39, 0.73, 0.03), 5);
  }
  {
    GaitRun x = run("gait_tetrapod_to_tripod.toml", {}, {{"after_ms = 5000", "after_ms = 6000"}}, 9500);
    const double t_switch = resolved(x, "gait.switch_ms");
    EXPECT_NEAR(t_switch, 5058 + 2 * 506, 15);  // the hind leg's lift-off two tetrapod cycles later
    std::printf("tetrapod -> tripod requested after 6000 ms: switch at %.0f ms\n", t_switch);
    EXPECT_EQ(x.gait_class(2500, 6000), 1.0);   // tetrapod until the request
    EXPECT_EQ(x.gait_class(t_switch + 550, 9500), 2.0);
  }
}

// (c) Malformed triggers: one-line errors naming file:line and the key or name.
TEST(GaitTransitions, MalformedTriggerErrors) {
  const std::string head = "[model]\ntype = \"three_legs\"\n";
  auto error_of = [&](const std::string& triggers) { return test::model_config_error(head + triggers); };
  auto expect = [&](const std::string& triggers, const std::string& want) {
    const std::string e = error_of(triggers);
    EXPECT_NE(e.find(want), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  };
  expect("[[triggers]]\nset = \"gait.switch_ms\"\nevent = \"hind.landing\"\n",
         "bad.toml:5: unknown event 'hind.landing' in [[triggers]]");
  expect("[[triggers]]\nset = \"gait.swich_ms\"\nevent = \"hind.liftoff\"\n",
         "bad.toml:4: unknown parameter 'gait.swich_ms'");
  expect("[[triggers]]\nset = \"gait.period_ms\"\nevent = \"hind.liftoff\"\n",
         "bad.toml:4: 'gait.period_ms' is not a command time");
  expect("[[triggers]]\nset = \"gait.switch_ms\"\nevent = \"hind.liftoff\"\ndelay = 3\n",
         "bad.toml:6: unknown key 'delay' in [[triggers]]");
  expect("[[triggers]]\nset = \"gait.switch_ms\"\nevent = \"hind.liftoff\"\nafter = \"gait.nope_ms\"\n",
         "bad.toml:6: unknown parameter 'gait.nope_ms' in [[triggers]] 'after'");
  expect("[[triggers]]\nset = \"gait.switch_ms\"\n", "bad.toml:3: a [[triggers]] entry needs 'set'");
  expect("[triggers]\nset = \"gait.switch_ms\"\n", "bad.toml:3: 'triggers' must be an array of tables");
  expect("[parameters]\n\"gait.switch_ms\" = 5000\n[[triggers]]\nset = \"gait.switch_ms\"\nevent = \"hind.liftoff\"\n",
         "bad.toml:6: 'gait.switch_ms' is set both in [parameters] and by a trigger");
  expect("[[triggers]]\nset = \"gait.switch_ms\"\nevent = \"hind.liftoff\"\ndelay_ms = -5\n",
         "bad.toml:6: 'delay_ms' must be >= 0");
}

// Forward sensitivities differentiate triggered times (tests/sensitivity/test_trigger_sensitivity.cpp);
// a triggered command time itself is not a free parameter: no sensitivity to it (one line
// naming it), by the simulator as by the sensitivity analysis.
TEST(GaitTransitions, NoSensitivityToATriggeredCommandTime) {
  auto cfg = config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/gait_tripod_to_tetrapod.toml");
  auto m = config::build_model(cfg);
  solver::Simulator sim(*m);
  const auto p = m->parameters().values();
  EXPECT_NO_THROW(sim.run(p, {0.0, 10.0}, {}, {m->parameters().index("middle.ctr.cpg_lev.g_app")}));
  try {
    sim.run(p, {0.0, 10.0}, {}, {m->parameters().index("gait.switch_ms")});
    ADD_FAILURE() << "sensitivity to a triggered command time accepted";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("no sensitivity to gait.switch_ms: it is set by the [[triggers]] event"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}
