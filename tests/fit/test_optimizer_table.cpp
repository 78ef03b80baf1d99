// The optimiser table (fit::optimizers()) drives parsing, the gradient check, the error
// messages and the --optimizer help: every row parses under its name, its aliases and its
// NLopt code; its flags agree with NLopt's own classification of the algorithm; the help and
// the unknown-optimizer error list every row; gradient rows are refused for the Cruse fit,
// which has no Jacobian, and accepted for the FTi fit, which has one.
#include <gtest/gtest.h>

#include "config/config.hpp"
#include "config/fit_section.hpp"

#include <nlopt.h>

#include <algorithm>
#include <cctype>
#include <string>

#include "common/error.hpp"
#include "cruse/cruse1980_fit.hpp"
#include "fit/optimizer.hpp"
#include "fit_test_util.hpp"

using namespace phasmid;

namespace {
std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string nlopt_code(const fit::OptimizerInfo& a) {
  return nlopt_algorithm_to_string(static_cast<nlopt_algorithm>(a.nlopt_algorithm));
}
}  // namespace

TEST(OptimizerTable, EveryRowParsesUnderItsNameAliasesAndNloptCode) {
  ASSERT_EQ(fit::optimizers().front().name, "ceres");  // the default of OptimizerOptions
  EXPECT_EQ(fit::OptimizerOptions{}.method, "ceres");
  for (const auto& a : fit::optimizers()) {
    SCOPED_TRACE(a.name);
    std::vector<std::string> spellings = a.aliases;
    spellings.push_back(a.name);
    spellings.push_back(lower(a.name));
    if (a.backend == fit::Backend::NLopt) spellings.push_back("nlopt:" + nlopt_code(a));  // nlopt:LN_BOBYQA
    for (const auto& s : spellings) {
      fit::OptimizerOptions o;
      o.method = "";
      fit::parse_optimizer(s, o);
      EXPECT_EQ(o.method, a.name) << s;
      EXPECT_EQ(&fit::optimizer_info(o), &a);
      EXPECT_EQ(fit::needs_jacobian(o), a.needs_gradient);
    }
  }
}

TEST(OptimizerTable, FlagsAgreeWithNloptsClassification) {
  // NLopt codes: G/L = global/local, then D/N = derivative/no derivative; "G_" = global with
  // a local sub-algorithm.
  size_t nlopt_rows = 0;
  for (const auto& a : fit::optimizers()) {
    SCOPED_TRACE(a.name);
    if (a.backend == fit::Backend::Ceres) {
      EXPECT_EQ(a.nlopt_algorithm, -1);
      EXPECT_TRUE(a.needs_gradient);
      continue;
    }
    ++nlopt_rows;
    ASSERT_GE(a.nlopt_algorithm, 0);
    ASSERT_LT(a.nlopt_algorithm, NLOPT_NUM_ALGORITHMS);
    const std::string code = nlopt_code(a);
    EXPECT_EQ(a.global, code[0] == 'G') << code;
    if (code.rfind("G_", 0) == 0) {
      ASSERT_FALSE(a.local.empty()) << code;
      const auto& local = fit::find_optimizer(a.local);
      EXPECT_EQ(local.backend, fit::Backend::NLopt);
      EXPECT_FALSE(local.global);
      EXPECT_EQ(a.needs_gradient, local.needs_gradient);
    } else {
      EXPECT_TRUE(a.local.empty()) << code;
      EXPECT_EQ(a.needs_gradient, code[1] == 'D') << code;
    }
    EXPECT_FALSE(a.robust_loss);
    EXPECT_FALSE(a.description.empty());
    nlopt_opt opt = nlopt_create(static_cast<nlopt_algorithm>(a.nlopt_algorithm), 2);
    ASSERT_NE(opt, nullptr);
    EXPECT_EQ(nlopt_get_algorithm(opt), static_cast<nlopt_algorithm>(a.nlopt_algorithm));
    nlopt_destroy(opt);
  }
  EXPECT_EQ(nlopt_rows, fit::optimizers().size() - 1);
}

TEST(OptimizerTable, HelpAndUnknownOptimizerErrorListEveryRow) {
  const std::string help = fit::optimizer_help();
  const std::string err = fittest::error_message([] {
    fit::OptimizerOptions o;
    fit::parse_optimizer("nlopt:NEWTON", o);
  });
  EXPECT_EQ(err.rfind("unknown optimizer 'nlopt:NEWTON' (expected one of ceres, nlopt:BOBYQA, ", 0), 0u) << err;
  EXPECT_EQ(err.find('\n'), std::string::npos) << err;
  EXPECT_EQ(fittest::error_message([] {
              fit::OptimizerOptions o;
              fit::parse_optimizer("levenberg", o);
            }).rfind("unknown optimizer 'levenberg' (expected one of ", 0),
            0u);
  for (const auto& a : fit::optimizers()) {
    SCOPED_TRACE(a.name);
    // One help line per row: name, kind, description.
    const std::string kind = std::string(a.global ? "global" : "local") + ", " + (a.needs_gradient ? "gradient" : "derivative-free");
    const size_t line = help.find("\n  " + a.name + " ");
    ASSERT_NE(line, std::string::npos) << help;
    const std::string text = help.substr(line + 1, help.find('\n', line + 1) - line - 1);
    EXPECT_NE(text.find(kind), std::string::npos) << text;
    EXPECT_NE(text.find(a.description), std::string::npos) << text;
    EXPECT_NE(err.find(a.name), std::string::npos) << err;
  }
  EXPECT_EQ(static_cast<size_t>(std::count(help.begin(), help.end(), '\n')), fit::optimizers().size()) << help;
}

TEST(OptimizerTable, GradientRowsAreRefusedForTheCruseFitWhichHasNoJacobian) {
  // The fit of the Cruse config as `phasmid fit` makes it: through the cruse1980 scenario.
  const config::Config cfg = config::load_config(fittest::source("configs/fit_cruse1980_switch.toml"));
  struct {
    fit::FitSpec spec;
    std::unique_ptr<fit::ResidualProblem> problem;
  } cf;
  const auto scenario = config::build_scenario(cfg);
  cf.spec = config::fit_spec(cfg, *scenario, {});
  cf.problem = scenario->make_fit(cf.spec);
  ASSERT_FALSE(cf.problem->has_jacobian());
  const std::string reason = cf.problem->no_jacobian_reason();
  ASSERT_FALSE(reason.empty());
  size_t refused = 0, accepted = 0;
  for (const auto& a : fit::optimizers()) {
    SCOPED_TRACE(a.name);
    fit::OptimizerOptions o;
    o.method = a.name;
    const std::string err = fittest::error_message([&] { fit::check_optimizer(*cf.problem, o); });
    if (!a.needs_gradient) {
      EXPECT_EQ(err, "");
      ++accepted;
      continue;
    }
    ++refused;
    const std::string head = "optimizer " + a.name + " needs a gradient but the model has none: " + reason + "; use one of ";
    EXPECT_EQ(err.rfind(head, 0), 0u) << err;
    EXPECT_EQ(err.find('\n'), std::string::npos) << err;
    std::string derivative_free;  // the suggestions are exactly the rows without a gradient
    for (const auto& b : fit::optimizers())
      if (!b.needs_gradient) derivative_free += (derivative_free.empty() ? "" : ", ") + b.name;
    EXPECT_EQ(err.substr(std::min(head.size(), err.size())), derivative_free);
  }
  EXPECT_EQ(refused, 5u);   // ceres, LBFGS, SLSQP, MMA, MLSL
  EXPECT_EQ(accepted, 7u);  // BOBYQA, COBYLA, NELDERMEAD, SBPLX, DIRECT_L, CRS2_LM, ISRES
}

TEST(OptimizerTable, EveryRowIsAcceptedForTheFtiFitWhichHasAJacobian) {
  auto cfg = config::load_config(fittest::source("configs/fti_mechanical.toml"));
  auto model = config::build_model(cfg);
  fit::Targets t;
  fit::KinematicTarget k;
  k.data = fittest::synthetic_fti({}, 100.0, 10.0, 0.5, 1);
  t.kinematics.push_back(k);
  fit::FitProblem p(*model, fittest::fti_parameters(*model), t, fit::ProblemSettings{});
  ASSERT_TRUE(p.has_jacobian());
  for (const auto& a : fit::optimizers()) {
    fit::OptimizerOptions o;
    o.method = a.name;
    EXPECT_EQ(fittest::error_message([&] { fit::check_optimizer(p, o); }), "") << a.name;
  }
}

TEST(OptimizerTable, RobustLossesOnlyWithRowsThatApplyThem) {
  const std::string base =
      "[model]\ntype = \"mechanical_joint\"\n[fit]\nloss = \"huber\"\n"
      "[[fit.feature]]\nname = \"middle.fti.angle_max_deg\"\nvalue = 110\ntolerance = 1\n"
      "[fit.parameters]\n\"middle.fti.b_v\" = { lower = 5, upper = 50 }\n";
  for (const auto& a : fit::optimizers()) {
    SCOPED_TRACE(a.name);
    auto cfg = config::parse_config(base, "loss.toml");
    auto m = config::build_model(cfg);
    fit::FitOverrides ov;
    ov.optimizer = a.name;
    const std::string err = fittest::error_message([&] { fit::load_fit_spec(cfg, *m, ov); });
    if (a.robust_loss) EXPECT_EQ(err, "");
    else EXPECT_EQ(err, "loss.toml:4: robust losses need one of ceres, not " + a.name);
  }
}
