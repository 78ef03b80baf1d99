// Forward sensitivities of the walking models' per-leg features (step period, stance and swing,
// duty factor, joint excursions in stance, protraction-in-stance fractions; docs/features.md)
// against central finite differences, on the middle leg with rate motoneurons (the same
// features as with spiking ones, several times cheaper). The parameters include the two
// crossing levels of those features, beta_thr_pr and syn.cpg_in.V_h, whose event times carry
// the extra term d level / dp of the implicit-function formula.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>

#include "config/config.hpp"
#include "fd_check.hpp"
#include "build_info.hpp"

using namespace phasmid;

TEST(LegFeatureSensitivity, PerLegFeaturesMatchCentralDifferences) {
  auto cfg = config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/middle_leg_forward.toml");
  cfg.table["model"].as_table()->insert_or_assign("motoneuron", "rate");
  auto m = config::build_model(cfg);
  auto o = sensitivity_test::feature_options(
      {"middle.ctr.cpg_lev.g_app", "middle.coupling.beta_thr_pr", "syn.cpg_in.V_h"}, 3600, 1500);
  auto [fwd, fd, fd2] = sensitivity_test::forward_and_fd(*m, o, 1e-10, 1e-11, 3e-5);
  ASSERT_EQ(fwd.features.size(), fd.features.size());
  const std::set<std::string> leg = {"middle.step_period_ms", "middle.stance_ms", "middle.swing_ms",
                                     "middle.duty_factor", "middle.thc.stance_change_deg", "middle.fti.stance_change_deg",
                                     "middle.protraction_in_stance_fraction", "middle.stance_retraction_fraction"};
  std::set<std::string> seen, compared;
  for (size_t f = 0; f < fwd.features.size(); ++f) {
    const std::string& name = fwd.features[f].name;
    if (!leg.count(name)) continue;
    seen.insert(name);
    for (size_t j = 0; j < o.parameters.size(); ++j) {
      const double a = fwd.absolute(f, j), b = fd.absolute(f, j);
      if (std::getenv("PHASMID_PRINT")) std::printf("%-42s %-28s fwd %+.6e fd %+.6e fd2 %+.6e\n", name.c_str(), o.parameters[j].c_str(), a, b, fd2.absolute(f, j));
      ASSERT_TRUE(std::isfinite(a)) << name << " / " << o.parameters[j] << ": no forward gradient";
      // Well conditioned: the finite difference does not depend on the step (two steps agree to
      // 0.25 %) and is not zero (a feature the parameter does not move).
      if (!sensitivity_test::fd_steps_agree(fd, fd2, f, j) || std::abs(b) < 1e-9) continue;
      EXPECT_NEAR(a, b, 0.01 * std::abs(b)) << name << " / " << o.parameters[j];
      compared.insert(name + " / " + o.parameters[j]);
    }
  }
  EXPECT_EQ(seen, leg) << "every per-leg feature of the leg model is computed";
  EXPECT_GE(compared.size(), 12u);
  // The level terms: the stance duration moves with the contact threshold, the fractions with
  // the retractor-CPG level.
  EXPECT_TRUE(compared.count("middle.stance_ms / middle.coupling.beta_thr_pr"));
  EXPECT_TRUE(compared.count("middle.protraction_in_stance_fraction / syn.cpg_in.V_h") ||
              compared.count("middle.stance_retraction_fraction / syn.cpg_in.V_h"));
}
