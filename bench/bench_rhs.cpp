// Cost of one model right-hand side in each scalar type the solver uses: double (f), and
// ceres::Jet<double, 1 | 4 | 8> (sensitivity right-hand sides and Jacobian columns), as a ratio
// to f measured in the same process, per lane of the Jet. Shows what the build's instruction
// set (CMake option PHASMID_NATIVE) does to the derivative lanes.
//   build/bench/bench_rhs [config ...]   (default: the single FTi joint, its rate-MN variant
//                                         and the middle leg)
#include <chrono>
#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

#include "config/config.hpp"
#include "build_info.hpp"

using namespace phasmid;

namespace {

// Microseconds per evaluation at the model's initial state (best of 5 blocks of `reps`); every
// derivative lane is seeded so that no lane is trivially zero.
template <class J>
double microseconds(const model::OdeModel& m, const std::vector<double>& y, const std::vector<double>& p, int reps) {
  std::vector<J> yj(y.size()), pj(p.size()), fj(y.size());
  for (size_t i = 0; i < p.size(); ++i) pj[i] = J(p[i]);
  for (size_t i = 0; i < y.size(); ++i) {
    yj[i] = J(y[i]);
    if constexpr (!std::is_same_v<J, double>)
      for (int k = 0; k < J::DIMENSION; ++k) yj[i].v[k] = 0.1 * (i + k + 1);
  }
  double best = 1e300, sink = 0.0;
  for (int block = 0; block < 5; ++block) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int r = 0; r < reps; ++r) {
      m.rhs(0.0, yj.data(), pj.data(), fj.data());
      if constexpr (std::is_same_v<J, double>) sink += fj[0];
      else sink += fj[0].a;
    }
    const auto t1 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double>(t1 - t0).count() / reps * 1e6);
  }
  if (sink == 0.123456789) std::printf(" ");  // keeps the evaluations from being optimised away
  return best;
}

void measure(const std::string& label, const model::OdeModel& m) {
  const auto p = m.parameters().values();
  const auto y = m.initial_state(p);
  const int reps = 4000;
  const double f = microseconds<double>(m, y, p, reps);
  const double j1 = microseconds<model::Jet1>(m, y, p, reps);
  const double j4 = microseconds<model::Jet4>(m, y, p, reps);
  const double j8 = microseconds<model::JetK>(m, y, p, reps);
  std::printf("%-44s %4zu  %8.3f  %6.2f  %6.2f  %6.2f  %8.2f  %8.2f\n", label.c_str(), y.size(), f, j1 / f, j4 / f,
              j8 / f, j4 / f / 4, j8 / f / 8);
}

}  // namespace

int main(int argc, char** argv) {
  std::printf("bench_rhs: one right-hand side per scalar type, relative to double (f); best of 5 x 4000 evaluations\n");
  std::printf("%-44s %4s  %8s  %6s  %6s  %6s  %8s  %8s\n", "model", "n", "f [us]", "Jet1", "Jet4", "Jet8",
              "Jet4/lane", "Jet8/lane");
  const std::string dir = std::string(PHASMID_SOURCE_DIR) + "/configs/";
  std::vector<std::string> configs;
  for (int a = 1; a < argc; ++a) configs.push_back(argv[a]);
  if (configs.empty()) {
    const auto fti = config::load_config(dir + "single_joint_fti.toml");
    measure("single_joint_fti.toml", *config::build_model(fti));
    std::string text = fti.text;
    text.insert(text.find("[model]") + 7, "\nmotoneuron = \"rate\"");
    measure("single_joint_fti.toml, motoneuron = \"rate\"", *config::build_model(config::parse_config(text, fti.path)));
    configs.push_back(dir + "middle_leg_forward.toml");
  }
  for (const auto& c : configs) {
    const auto cfg = config::load_config(c);
    measure(c.substr(c.find_last_of('/') + 1), *config::build_model(cfg));
  }
  return 0;
}
