// The KLU path's Jacobian comes from coloured forward-mode AD (columns that share no row are
// differentiated together; src/solver/simulator.cpp). It must equal the full AD Jacobian at
// states along a real trajectory, including after the central commands (levator release,
// intersegmental couplings) that are off when the sparsity pattern is sampled.
#include <gtest/gtest.h>

#include <cmath>

#include "model/leg_network.hpp"
#include "solver/simulator.hpp"

using namespace phasmid;

namespace {
void expect_sparse_equals_dense(const model::OdeModel& m, double t, size_t max_colors) {
  auto p = m.parameters().values();
  solver::SolverOptions o;
  o.rtol = o.atol = 1e-6;
  auto r = solver::Simulator(m, o).run(p, {0.0, t});
  std::vector<double> y(r.y.begin() + m.num_states(), r.y.end());
  size_t colors = 0;
  auto Js = solver::jacobian_sparse_autodiff(m, t, y, p, &colors);
  auto Jd = solver::jacobian_autodiff(m, t, y, p);
  const size_t n = m.num_states();
  for (size_t j = 0; j < n; ++j)
    for (size_t i = 0; i < n; ++i)
      EXPECT_NEAR(Js[j * n + i], Jd[j * n + i], 1e-12 * (1.0 + std::abs(Jd[j * n + i])))
          << m.states()[i].name << " wrt " << m.states()[j].name;
  EXPECT_LE(colors, max_colors);  // what makes it cheap: 6 AD directions (measured) instead of n
}
}  // namespace

TEST(SparseJacobian, ColouredEqualsFullAutodiff) {
  model::LegOptions o;
  o.thc_set = "A.17";
  expect_sparse_equals_dense(*model::build_leg_model("middle", o), 700.0, 10);
  model::ThreeLegOptions t;
  t.motoneuron = model::MotoneuronModel::Rate;
  expect_sparse_equals_dense(*model::build_three_leg_model(t), 2000.0, 10);
}
