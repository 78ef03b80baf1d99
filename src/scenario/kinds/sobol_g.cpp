// Model kind "sobol_g": Sobol's G function on six inputs,
//   y = prod_i (|4 x_i - 2| + a_i) / (1 + a_i),  x_i in [0, 1],
// a test of global sensitivity analysis with closed-form indices (docs/gsa.md): with x uniform,
// V_i = 1 / (3 (1 + a_i)^2) and S1_i = V_i / (prod_k (1 + V_k) - 1). The default coefficients
// a = (78, 12, 0.5, 2, 97, 33) are SALib's (Saltelli et al. 2008, Global Sensitivity Analysis:
// The Primer, Sect. 3.6).
#include <cmath>
#include <string>

#include "scenario/kinds/analytic_kind.hpp"

namespace phasmid::scenario {

ModelKind sobol_g_kind() {
  return {"sobol_g", "Sobol' G function of six inputs y = prod (|4 x_i - 2| + a_i)/(1 + a_i) (test function of docs/gsa.md)",
          {}, [](const ModelSection&) {
            constexpr int kInputs = 6;
            const double a[kInputs] = {78, 12, 0.5, 2, 97, 33};
            kinds::AnalyticFunction f;
            f.kind = "sobol_g";
            for (int i = 0; i < kInputs; ++i)
              f.parameters.add({"x" + std::to_string(i + 1), 0.5, "1", "Sobol' (1993)", "input, usually uniform on [0, 1]", 0.0, 1.0});
            for (int i = 0; i < kInputs; ++i)
              f.parameters.add({"a" + std::to_string(i + 1), a[i], "1", "Saltelli et al. (2008), Sect. 3.6",
                                "importance coefficient of x" + std::to_string(i + 1) + " (small: important)", 0.0});
            f.y_description = "prod_i (|4 x_i - 2| + a_i) / (1 + a_i)";
            f.y = [](const std::vector<double>& p) {
              double g = 1;
              for (int i = 0; i < kInputs; ++i) g *= (std::fabs(4 * p[i] - 2) + p[kInputs + i]) / (1 + p[kInputs + i]);
              return g;
            };
            return kinds::make_analytic_scenario(std::move(f));
          }};
}

}  // namespace phasmid::scenario
