// Knops 2013 Section 3.3 (Figs. 3.24-3.27): gait transitions both ways by central inhibition
// of the levator CPGs and reset (configs/gait_*.toml: tetrapod -> tripod successively from
// 5050 ms, the legs held in stance one after the other; tripod -> tetrapod with all legs held
// at 5000 ms and released from 6000 ms). Gait class from the lift-off phase lags before
// (2500-5000 ms) and after (6900-8500 ms) the transition.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <tuple>

#include "config/config.hpp"
#include "features/features.hpp"

using namespace phasmid;

namespace {
std::tuple<double, double, double> classes(const std::string& config) {
  auto cfg = config::load_config(std::string(PHASMID_SOURCE_DIR) + "/configs/" + config);
  auto m = config::build_model(cfg);
  auto s = config::simulation_settings(cfg);
  solver::Simulator sim(*m, s.solver);
  auto r = sim.run(m->parameters().values(), solver::output_grid(8500, 5.0), features::feature_roots(*m));
  auto window = [&](double t0, double t1) {
    solver::SolveResult w = r;
    w.events.erase(std::remove_if(w.events.begin(), w.events.end(), [&](const solver::Event& e) { return e.t > t1; }),
                   w.events.end());
    features::FeatureOptions fo;
    fo.discard_ms = t0;
    std::map<std::string, double> f;
    for (auto& x : features::compute_features(*m, w, fo)) f[x.name] = x.value;
    return f.count("gait_class") ? f["gait_class"] : -1.0;
  };
  return {window(2500, 5000), window(6900, 8500), window(5600, 8500)};
}
}  // namespace

TEST(GaitTransitions, TetrapodToTripod) {
  auto [before, after, early] = classes("gait_tetrapod_to_tripod.toml");
  EXPECT_EQ(before, 1.0);  // tetrapod
  EXPECT_EQ(after, 2.0);   // tripod
  EXPECT_EQ(early, 2.0);   // successively, within one cycle: tripod from 5600 ms (Fig. 3.25)
}

TEST(GaitTransitions, TripodToTetrapod) {
  auto [before, after, early] = classes("gait_tripod_to_tetrapod.toml");
  (void)early;  // all legs held 5000-6000 ms: no gait in that window
  EXPECT_EQ(before, 2.0);
  EXPECT_EQ(after, 1.0);
}
