// The feature catalogue (features::feature_catalogue) against what compute_features returns:
// for every model kind, built from its shipped config (network models with rate motoneurons
// and shorter runs, so that the whole file runs in seconds), every feature returned is in the
// catalogue with the same unit, and for runs long enough for every feature the two lists are
// the same. Every differentiable catalogue entry of the leg model gets a finite gradient from
// compute_feature_gradients, gait_class none. Also the declared structure of the walking models.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>

#include "config/config.hpp"
#include "features/features.hpp"
#include "build_info.hpp"

using namespace phasmid;

namespace {

struct Case {
  const char* config;
  bool rate;           // switch the network's motoneurons to the rate formulation
  double t_end_ms;     // shortened run
  double discard_ms;
  bool complete;       // the run is long enough for every catalogue feature
};

config::Config load(const Case& c) {
  auto cfg = config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/" + c.config);
  if (c.rate) cfg.table["model"].as_table()->insert_or_assign("motoneuron", "rate");
  return cfg;
}

solver::SolveResult run(const model::OdeModel& m, const config::Config& cfg, const Case& c,
                        const std::vector<size_t>& sens = {}) {
  config::SimulationSettings s = config::simulation_settings(cfg);
  solver::Simulator sim(m, s.solver);
  const std::vector<double> p = m.parameters().values();
  return sim.run(p, solver::output_grid(c.t_end_ms, 5.0), features::feature_roots(m, p), sens);
}

std::map<std::string, features::FeatureInfo> by_name(const std::vector<features::FeatureInfo>& cat) {
  std::map<std::string, features::FeatureInfo> out;
  for (const auto& f : cat) EXPECT_TRUE(out.emplace(f.name, f).second) << "listed twice: " << f.name;
  return out;
}

class FeatureCatalogue : public ::testing::TestWithParam<Case> {};

TEST_P(FeatureCatalogue, ListsEveryComputedFeatureWithItsUnit) {
  const Case c = GetParam();
  const config::Config cfg = load(c);
  auto m = config::build_model(cfg);
  const auto cat = by_name(features::feature_catalogue(*m));
  ASSERT_FALSE(cat.empty()) << c.config;
  features::FeatureOptions fo;
  fo.discard_ms = c.discard_ms;
  const auto feats = features::compute_features(*m, run(*m, cfg, c), fo);
  ASSERT_FALSE(feats.empty()) << c.config;
  std::set<std::string> computed;
  for (const auto& f : feats) {
    computed.insert(f.name);
    auto it = cat.find(f.name);
    ASSERT_NE(it, cat.end()) << c.config << ": '" << f.name << "' is computed but not in the catalogue";
    EXPECT_EQ(it->second.unit, f.unit) << c.config << ": " << f.name;
    EXPECT_FALSE(it->second.description.empty()) << f.name;
  }
  if (c.complete)
    for (const auto& [name, info] : cat) EXPECT_TRUE(computed.count(name)) << c.config << ": '" << name << "' is never computed";
}

// Section 3.1 joint, single FTi network, middle leg, three legs, curve walking, CTr-FTi pair.
INSTANTIATE_TEST_SUITE_P(
    ModelKinds, FeatureCatalogue,
    ::testing::Values(Case{"fti_mechanical.toml", false, 3000, 500, true},
                      Case{"single_joint_fti.toml", true, 3000, 500, true},
                      Case{"middle_leg_forward.toml", true, 3600, 1500, true},
                      Case{"three_legs_tetrapod.toml", true, 5000, 2500, true},
                      Case{"curve_walking.toml", true, 3500, 2000, true},
                      Case{"coupled_ctr_fti.toml", false, 3000, 500, true}),
    [](const ::testing::TestParamInfo<Case>& i) {
      std::string n = i.param.config;
      return n.substr(0, n.find('.'));
    });

TEST(FeatureCatalogue, WalkingModelsListTheirLegsFeatures) {
  auto tl = config::build_model(load({"three_legs_tetrapod.toml", true, 0, 0, false}));
  const auto cat = by_name(features::feature_catalogue(*tl));
  for (const char* n : {"hind.step_period_ms", "front.duty_factor", "middle.thc.stance_change_deg",
                        "middle.stance_retraction_fraction", "phase_lag.hind_to_middle", "phase_lag.hind_to_front"})
    EXPECT_TRUE(cat.count(n)) << n;
  ASSERT_TRUE(cat.count("gait_class"));
  EXPECT_FALSE(cat.at("gait_class").differentiable);
  EXPECT_TRUE(cat.at("phase_lag.hind_to_middle").differentiable);
  EXPECT_TRUE(cat.count("middle.fti.phase_lag")) << "phase lag of every channel after the first";
  EXPECT_FALSE(cat.count("front.thc.phase_lag")) << "the first channel has no lag to itself";
  // 9 channels x 7 + 8 lags + global period, 3 legs x 8, 4 leg pairs, gait_class, and the
  // derived 0/1 features oscillates, is_tripod, is_tetrapod.
  EXPECT_EQ(cat.size(), 9u * 7 + 8 + 1 + 3 * 8 + 4 + 1 + 3);
  for (const char* n : {"oscillates", "is_tripod", "is_tetrapod"}) {
    ASSERT_TRUE(cat.count(n)) << n;
    EXPECT_FALSE(cat.at(n).differentiable) << n;
    EXPECT_EQ(cat.at(n).unit, "1") << n;
  }
  auto mj = config::build_model(load({"fti_mechanical.toml", false, 0, 0, false}));
  // One channel: global period + 7 channel features + oscillates, no leg features.
  EXPECT_EQ(features::feature_catalogue(*mj).size(), 9u);
}

TEST(FeatureCatalogue, EveryDifferentiableFeatureHasAGradient) {
  const Case c{"middle_leg_forward.toml", true, 3600, 1500, true};
  const config::Config cfg = load(c);
  auto m = config::build_model(cfg);
  const std::vector<size_t> sens = {m->parameters().index("middle.ctr.cpg_lev.g_app"),
                                    m->parameters().index("middle.coupling.beta_thr_pr")};
  features::FeatureOptions fo;
  fo.discard_ms = c.discard_ms;
  const auto grads = features::compute_feature_gradients(*m, run(*m, cfg, c, sens), fo);
  std::map<std::string, Eigen::VectorXd> g;
  for (const auto& x : grads) g[x.feature.name] = x.gradient;
  size_t checked = 0;
  for (const auto& f : features::feature_catalogue(*m)) {
    if (!f.differentiable) continue;
    ASSERT_TRUE(g.count(f.name)) << f.name << ": no gradient";
    ASSERT_EQ(g[f.name].size(), 2) << f.name;
    EXPECT_TRUE(std::isfinite(g[f.name][0]) && std::isfinite(g[f.name][1])) << f.name;
    ++checked;
  }
  // 3 channels x 7 + 2 lags + global period, 8 features of the one leg.
  EXPECT_EQ(checked, 3u * 7 + 2 + 1 + 8);
  // The LD drive moves the step period (leg model: 510 ms LD rhythm, Section 3.2).
  EXPECT_GT(std::abs(g.at("middle.step_period_ms")[0]), 1.0);
}

TEST(ModelStructure, WalkingModelsDeclareTheirContactLegs) {
  auto tl = config::build_model(load({"three_legs_tetrapod.toml", true, 0, 0, false}));
  const auto& st = tl->structure();
  ASSERT_EQ(st.contact_legs.size(), 3u);
  const char* legs[] = {"front", "middle", "hind"};
  for (size_t i = 0; i < 3; ++i) {
    const model::ContactLeg& l = st.contact_legs[i];
    EXPECT_EQ(l.leg, legs[i]);
    EXPECT_EQ(tl->states()[l.beta_state].name, l.leg + ".ctr.beta");
    EXPECT_EQ(tl->parameters().at(l.threshold_param).value, 38.0);  // Section 3.2
    ASSERT_TRUE(l.retractor_state.has_value());
    EXPECT_EQ(tl->states()[*l.retractor_state].name, l.leg + ".thc.cpg_ret.V");
    EXPECT_EQ(tl->parameters().at(l.retractor_level_param).name, "syn.cpg_in.V_h");
  }
  ASSERT_TRUE(st.contralateral.has_value());
  EXPECT_NEAR(tl->parameters().at(st.contralateral->lag_param).value, 1.0 / 3, 1e-15);  // tetrapod lag
  EXPECT_EQ(tl->parameters().at(st.contralateral->period_param).value, 510.0);       // T_4pod
  EXPECT_FALSE(st.body.has_value());
  // Fig. 2.14: 72 neurons, plus each leg's levator-hold command neuron (start times).
  EXPECT_EQ(st.neurons.size(), 72u + 3);
  EXPECT_EQ(st.neurons.back().name, "hind.ld_hold");
  EXPECT_EQ(tl->states()[st.neurons.front().v_state].name, "front.thc.cpg_ret.V");
  EXPECT_EQ(tl->contact_leg("L2"), nullptr);

  auto cw = config::build_model(load({"curve_walking.toml", true, 0, 0, false}));
  ASSERT_TRUE(cw->structure().body.has_value());
  EXPECT_EQ(cw->structure().body->left_leg, "L2");
  EXPECT_EQ(cw->parameters().at(cw->structure().body->reach_param).value, 15.0);
  ASSERT_NE(cw->contact_leg("R2"), nullptr);
  EXPECT_FALSE(cw->structure().contralateral.has_value());

  auto sj = config::build_model(load({"single_joint_fti.toml", false, 0, 0, false}));
  EXPECT_TRUE(sj->structure().contact_legs.empty());
  EXPECT_EQ(sj->structure().neurons.size(), 8u);  // Fig. 2.12: one joint network
}

}  // namespace
