// Model kind "ishigami": the Ishigami & Homma (1990) function
//   y = sin x1 + a sin^2 x2 + b x3^4 sin x1,
// the standard test of global sensitivity analysis (docs/gsa.md). With a = 7, b = 0.1 and
// x uniform on [-pi, pi]^3 its Sobol' indices are known in closed form (Sobol' & Levitan 1999):
// S1 = (0.3139, 0.4424, 0), ST = (0.5576, 0.4424, 0.2437), S2(1,3) = 0.2437.
#include <cmath>

#include "scenario/kinds/analytic_kind.hpp"

namespace phasmid::scenario {

ModelKind ishigami_kind() {
  return {"ishigami", "Ishigami function y = sin x1 + a sin^2 x2 + b x3^4 sin x1 (test function of docs/gsa.md)", {},
          [](const ModelSection&) {
            constexpr double kPi = 3.14159265358979323846;
            kinds::AnalyticFunction f;
            f.kind = "ishigami";
            for (const char* x : {"x1", "x2", "x3"})
              f.parameters.add({x, 0.0, "1", "Ishigami & Homma (1990)", "input, usually uniform on [-pi, pi]", -kPi, kPi});
            f.parameters.add({"a", 7.0, "1", "Ishigami & Homma (1990); SALib's test value", "weight of sin^2 x2"});
            f.parameters.add({"b", 0.1, "1", "Ishigami & Homma (1990); SALib's test value", "weight of x3^4 sin x1"});
            f.y_description = "sin x1 + a sin^2 x2 + b x3^4 sin x1";
            f.y = [](const std::vector<double>& p) {
              const double s2 = std::sin(p[1]);
              return std::sin(p[0]) + p[3] * s2 * s2 + p[4] * std::pow(p[2], 4) * std::sin(p[0]);
            };
            return kinds::make_analytic_scenario(std::move(f));
          }};
}

}  // namespace phasmid::scenario
