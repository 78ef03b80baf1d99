// Forward sensitivities through command times set by [[triggers]] (docs/sensitivity.md): the
// triggered time moves with the parameters through its event, d tau / dp = d t_event / dp
// (implicit-function formula at the event), and the sensitivities jump at tau by
// (f(tau-) - f(tau+)) d tau / dp. A middle leg with the direction switch and rate motoneurons
// (as tests/solver/test_command_triggers.cpp, shorter): backward stepping from a touch-down
// (delay 0: the jump at the event itself), forward again 150 ms after the next lift-off (a
// breakpoint added later: the jump there, with d tau / dp found at the lift-off; a chain, since
// that trigger is armed by the first command). Against central finite differences, which re-run
// the triggers; and against the same run with the found times fixed, whose forward
// sensitivities lack the d tau / dp terms (they would fail).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <string>

#include "config/config.hpp"
#include "features/features.hpp"
#include "fd_check.hpp"
#include "../solver/middle_leg_trigger_config.hpp"

using namespace phasmid;

namespace {
// Backward from the first touch-down after 900 ms, forward 150 ms after the next lift-off.
const std::string kConfig = test::middle_leg_trigger_config(900, 150);
constexpr double kTEnd = 2600, kDiscard = 700;
}  // namespace

TEST(TriggerSensitivity, TriggeredCommandTimesMatchCentralDifferences) {
  auto cfg = config::parse_config(kConfig, "trigsens.toml");
  auto m = config::build_model(cfg);
  const std::vector<std::string> params = {"middle.ctr.cpg_lev.g_app", "middle.coupling.beta_thr_pr",
                                           "middle.ctr.cpg_dep.g_app"};
  auto o = sensitivity_test::feature_options(params, kTEnd, kDiscard);
  auto [fwd, fd, fd2] = sensitivity_test::forward_and_fd(*m, o, 1e-10, 1e-11, 3e-5);
  ASSERT_EQ(fwd.features.size(), fd.features.size());

  // The times the triggers found; the same run with them fixed (--set): forward sensitivities
  // without the d tau / dp terms.
  solver::SolverOptions so;
  so.rtol = so.atol = 1e-10;
  auto found = solver::Simulator(*m, so).run(m->parameters().values(), solver::output_grid(kTEnd, 5),
                                             features::feature_roots(*m));
  ASSERT_EQ(found.commands.size(), 2u) << "both triggers fire";
  std::vector<std::string> sets;
  for (const auto& c : found.commands) {
    char s[96];
    std::snprintf(s, sizeof s, "%s=%.17g", m->parameters().at(c.parameter).name.c_str(), c.t_ms);
    sets.push_back(s);
    std::printf("%s ms\n", s);
  }
  ASSERT_LT(found.commands[0].t_ms, kTEnd - 600);  // backward and forward stepping after the discard
  ASSERT_GT(found.commands[0].t_ms, kDiscard);
  auto fixed_model = config::build_model(cfg, sets);
  ASSERT_TRUE(fixed_model->triggers().empty());
  o.solver.rtol = o.solver.atol = 1e-10;
  auto fixed = sensitivity::analyse_sensitivities(*fixed_model, fixed_model->parameters().values(), o);
  ASSERT_EQ(fixed.features.size(), fwd.features.size());

  std::set<std::string> compared, jump_matters;
  for (size_t f = 0; f < fwd.features.size(); ++f) {
    const std::string& name = fwd.features[f].name;
    // Same trajectory, so the same feature values.
    EXPECT_NEAR(fixed.features[f].value, fwd.features[f].value, 1e-6 * std::max(1.0, std::abs(fwd.features[f].value)))
        << name;
    for (size_t j = 0; j < params.size(); ++j) {
      const double a = fwd.absolute(f, j), b = fd.absolute(f, j), c = fixed.absolute(f, j);
      if (std::getenv("PHASMID_PRINT"))
        std::printf("%-40s %-28s fwd %+.6e fd %+.6e fd2 %+.6e fixed-times %+.6e\n", name.c_str(), params[j].c_str(), a,
                    b, fd2.absolute(f, j), c);
      ASSERT_TRUE(std::isfinite(a)) << name << " / " << params[j] << ": no forward gradient";
      // Well conditioned: the two steps agree to 0.25 % and the difference is not zero.
      if (!sensitivity_test::fd_steps_agree(fd, fd2, f, j) || std::abs(b) < 1e-9) continue;
      EXPECT_NEAR(a, b, 0.01 * std::abs(b)) << name << " / " << params[j];
      compared.insert(name + " / " + params[j]);
      // The d tau / dp terms are significant: without them the derivative is off by > 10 %.
      if (std::abs(c - b) > 0.1 * std::abs(b)) jump_matters.insert(name + " / " + params[j]);
    }
  }
  std::printf("%zu well-conditioned pairs compared, %zu where the triggered-time terms change the derivative by > 10 %%\n",
              compared.size(), jump_matters.size());
  // Measured: 55 pairs, 6 of them (the ThC's maximum and stance excursion, to each parameter)
  // with the terms > 10 %; e.g. d angle_max_deg / d cpg_dep.g_app = -1057.45 forward, -1057.46
  // central differences, -18.1 with the times fixed. (Before the IN3/IN7/IN11 drive change and
  // the rate-MN recalibration: 58 pairs, 9 with the terms > 10 %, the ThC's retraction time
  // among them; its finite differences are no longer well conditioned.)
  EXPECT_GE(compared.size(), 50u);
  EXPECT_GE(jump_matters.size(), 6u);
  // A drive that moves the events, and the triggers' own threshold (the dg/dp term).
  for (const char* p : {"middle.ctr.cpg_lev.g_app", "middle.coupling.beta_thr_pr", "middle.ctr.cpg_dep.g_app"})
    EXPECT_TRUE(jump_matters.count(std::string("middle.thc.angle_max_deg / ") + p)) << p;
}
