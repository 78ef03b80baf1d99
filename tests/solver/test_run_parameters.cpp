// The run's parameter vector has one owner (solver/run_parameters.hpp): a part registered with
// it is bound at once and again, to the new values, after every set(); a Jet mirror takes the
// values at registration and every value set later; the others stay as they were.
#include <gtest/gtest.h>

#include <vector>

#include "solver/run_parameters.hpp"

using namespace phasmid;

namespace {

// Records the values it was bound to.
class RecordingPart : public model::OdeModelPart {
 public:
  void bind(const double* p) override { bound.emplace_back(p, p + 3); }
  void rhs(double, const double*, const double*, double*) const override {}
  void rhs(double, const model::JetK*, const model::JetK*, model::JetK*) const override {}
  std::vector<std::vector<double>> bound;
};

}  // namespace

TEST(RunParameters, SetKeepsEveryMirrorAndBoundPartInStep) {
  solver::RunParameters params({1.0, 2.0, 3.0});
  RecordingPart a, b;
  std::vector<model::JetK> jets;
  std::vector<model::Jet1> jets1;
  params.bind(&a);
  params.mirror(jets);
  params.mirror(jets1);
  params.bind(&b);
  ASSERT_EQ(a.bound.size(), 1u);
  EXPECT_EQ(a.bound[0], (std::vector<double>{1.0, 2.0, 3.0}));
  ASSERT_EQ(jets.size(), 3u);
  EXPECT_EQ(jets[2].a, 3.0);

  params.set({0, 2}, 7.5);
  EXPECT_EQ(params.values(), (std::vector<double>{7.5, 2.0, 7.5}));
  for (const RecordingPart* part : {&a, &b}) {
    ASSERT_EQ(part->bound.size(), 2u);
    EXPECT_EQ(part->bound.back(), params.values());
  }
  for (size_t q = 0; q < 3; ++q) {
    EXPECT_EQ(jets[q].a, params.values()[q]) << q;
    EXPECT_EQ(jets1[q].a, params.values()[q]) << q;
    for (int k = 0; k < model::JetK::DIMENSION; ++k) EXPECT_EQ(jets[q].v[k], 0.0);
  }
}
