// Steady-cycle sensitivities (continuation/cycle_sensitivity.hpp, docs/sensitivity.md):
// - the relay oscillator, whose cycle is known in closed form: its period's derivatives and
//   those of its state on the section, through switches at events (saltation terms);
// - the single FTi joint with rate motoneurons: 30 (feature, parameter) pairs drawn at random
//   (seeded) over all its parameters and features, against central differences of the
//   converged cycle's features, themselves shown converged (steps h and 2h agree);
// - the spiking single joint, whose orbit does not close: one line naming the measure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <cstdio>
#include <cstring>
#include <map>
#include <utility>
#include <random>
#include <string>

#include "common/error.hpp"
#include "config/config.hpp"
#include "continuation/cycle_sensitivity.hpp"
#include "continuation/sensitivity_job.hpp"
#include "model/ode_model.hpp"

using namespace phasmid;
using namespace phasmid::continuation;

namespace {

std::unique_ptr<model::OdeModel> make(const std::string& keys) {
  return config::build_model(config::parse_config("[model]\n" + keys, "test"));
}

sensitivity::SensitivityOptions tight_options(std::vector<std::string> parameters, double rtol) {
  sensitivity::SensitivityOptions o;
  o.parameters = std::move(parameters);
  o.write_trajectory = false;
  o.solver.rtol = o.solver.atol = rtol;
  o.solver.progress = false;
  return o;
}

// The relay's cycle in closed form (src/scenario/kinds/relay_oscillator.cpp): period
// T = 2 tau ln((1+a)/(1-a)); z relaxes to +-c/k on each half period, so at the switch to u = -1
// z = (c/k) tanh(k T/4), and at the section (x rising through 0, tau ln(1+a) after the switch
// to u = +1) z = (c/k) (1 - (1 + tanh(k T/4)) exp(-k tau ln(1+a))).
struct RelayCycle {
  double T, z;
};
RelayCycle relay_cycle(double a, double tau, double k, double c) {
  const double T = 2 * tau * std::log((1 + a) / (1 - a));
  return {T, c / k * (1 - (1 + std::tanh(k * T / 4)) * std::exp(-k * tau * std::log(1 + a)))};
}

}  // namespace

TEST(CycleSensitivity, RelayOscillatorPeriodAndSectionStateAgainstTheClosedForm) {
  auto m = make("type = \"relay_oscillator\"\n");
  const std::vector<std::string> names = {"relay.a", "relay.tau_ms", "relay.k", "relay.c"};
  CycleSensitivityOptions co;
  co.shooting.section = {0, 0.0, +1};
  co.shooting.transient_ms = 300;
  co.shooting.max_period_ms = 100;
  co.shooting.tolerance = 1e-10;
  const auto p = m->parameters().values();
  const CycleSensitivity r = analyse_cycle_sensitivities(*m, p, tight_options(names, 1e-11), co);
  double q[4];
  for (size_t j = 0; j < 4; ++j) q[j] = p[m->parameters().index(names[j])];
  const RelayCycle nominal = relay_cycle(q[0], q[1], q[2], q[3]);
  EXPECT_NEAR(r.cycle.period_ms, nominal.T, 1e-7);
  EXPECT_NEAR(r.cycle.y0[1], nominal.z, 1e-7);
  const size_t z = m->state_index("relay.z");
  for (size_t j = 0; j < 4; ++j) {
    // Derivatives of the closed form by central differences (smooth: h = 1e-5 relative is exact to ~1e-9).
    double qp[4], qm[4];
    std::copy(q, q + 4, qp), std::copy(q, q + 4, qm);
    const double h = 1e-5 * q[j];
    qp[j] += h, qm[j] -= h;
    const RelayCycle up = relay_cycle(qp[0], qp[1], qp[2], qp[3]), dn = relay_cycle(qm[0], qm[1], qm[2], qm[3]);
    EXPECT_NEAR(r.dperiod[j], (up.T - dn.T) / (2 * h), 1e-6 * std::max(1.0, std::abs(r.dperiod[j]))) << names[j];
    EXPECT_NEAR(r.dstate(z, j), (up.z - dn.z) / (2 * h), 1e-6 * std::max(1.0, std::abs(r.dstate(z, j)))) << names[j];
    EXPECT_EQ(r.dstate(0, j), 0.0) << "x is held on the section";
  }
  // Exactly: the period does not depend on z's rates, and dT/dtau = T/tau, dT/da = 4 tau/(1 - a^2).
  EXPECT_NEAR(r.dperiod[1], nominal.T / q[1], 1e-6);
  EXPECT_NEAR(r.dperiod[0], 4 * q[1] / (1 - q[0] * q[0]), 1e-5);
  EXPECT_NEAR(r.dperiod[2], 0.0, 1e-7);
  EXPECT_NEAR(r.dperiod[3], 0.0, 1e-7);
}

// 30 (feature, parameter) pairs of the single FTi joint with rate motoneurons, drawn with a
// fixed seed over all its parameters and all its features, against central differences of the
// features of the converged cycle (cycle_features: Newton at p -+ h, rtol 1e-10). Each pair's
// differences are shown converged first: the quotients at relative steps h and 2h agree within
// 0.1 % or `zero`, for the first h of 1e-4, 1e-3, 1e-2 where they do (a small step lets the
// cycle's integration noise into the quotient, a large one its curvature). Agreement: 0.5 %
// relative, or `zero` for zero derivatives, where `zero` is 1e-5 in relative sensitivity
// (|p/F| dF/dp): an absolute bound in the parameter's and the feature's own units would mean
// something else for each pair, and a derivative such as the period's by a parameter that
// moves flexion and extension by +-1732 ms per unit is a difference at the integration's
// relative accuracy of those. The table is printed.
TEST(CycleSensitivity, SingleJointRatePairsAgainstConvergedDifferences) {
  auto m = make("type = \"single_joint\"\nleg = \"middle\"\njoint = \"fti\"\nmotoneuron = \"rate\"\n");
  CycleSensitivityOptions co = default_cycle_options(*m);
  co.shooting.transient_ms = 4000;
  co.shooting.max_period_ms = 1000;
  const auto p = m->parameters().values();
  const auto all = sensitivity::select_parameters(*m, {});
  std::mt19937 rng(20261202);
  std::vector<std::string> drawn;
  for (int i = 0; i < 30; ++i) drawn.push_back(m->parameters().at(all[rng() % all.size()]).name);
  std::sort(drawn.begin(), drawn.end());
  drawn.erase(std::unique(drawn.begin(), drawn.end()), drawn.end());
  // Forward at the mode's default tolerance (CycleSensitivityOptions::max_rtol, 1e-8).
  const CycleSensitivity fwd = analyse_cycle_sensitivities(*m, p, tight_options(drawn, 1e-8), co);
  const size_t nf = fwd.report.features.size();
  ASSERT_GE(nf, 5u);
  CycleSensitivityOptions fine = co;
  fine.shooting.solver = tight_options({}, 1e-10).solver;
  fine.shooting.tolerance = 1e-6;
  // Features at p -+ h for parameter j and relative step rel, computed once each.
  std::map<std::pair<size_t, double>, std::pair<std::vector<features::Feature>, std::vector<features::Feature>>> runs;
  auto quotient = [&](size_t f, size_t j, double rel) {
    const size_t k = m->parameters().index(drawn[j]);
    const double h = rel * std::max(std::abs(p[k]), 1e-8);
    auto& run = runs[{j, rel}];
    if (run.first.empty()) {
      std::vector<double> pp = p, pm = p;
      pp[k] += h, pm[k] -= h;
      run = {cycle_features(*m, pp, fwd.cycle, fine), cycle_features(*m, pm, fwd.cycle, fine)};
    }
    auto value = [&](const std::vector<features::Feature>& fs) {
      for (const auto& x : fs)
        if (x.name == fwd.report.features[f].name) return x.value;
      return static_cast<double>(NAN);
    };
    return (value(run.first) - value(run.second)) / (2 * h);
  };
  std::mt19937 pick(7);
  for (int i = 0; i < 30; ++i) {
    const size_t f = pick() % nf, j = pick() % drawn.size();
    const std::string pair = fwd.report.features[f].name + " by " + drawn[j];
    const double zero = 1e-5 * std::abs(fwd.report.features[f].value / fwd.report.parameter_values[j]);
    double d = NAN, d2 = NAN, step = 0;
    for (double rel : {1e-4, 1e-3, 1e-2}) {
      d = quotient(f, j, rel), d2 = quotient(f, j, 2 * rel), step = rel;
      if (std::abs(d - d2) <= std::max(1e-3 * std::abs(d), zero)) break;
    }
    ASSERT_LE(std::abs(d - d2), std::max(1e-3 * std::abs(d), zero)) << "differences not converged: " << pair;
    const double a = fwd.report.absolute(f, j);
    EXPECT_NEAR(a, d, std::max(5e-3 * std::abs(d), zero)) << pair;
    std::printf("%-32s %-28s forward %+.6e  differences %+.6e (step %g)\n", fwd.report.features[f].name.c_str(),
                drawn[j].c_str(), a, d, step);
  }
  // The period feature is the implicit-function dT/dp.
  const size_t period = fwd.report.feature_index("period_ms");
  for (size_t j = 0; j < drawn.size(); ++j)
    EXPECT_NEAR(fwd.report.absolute(period, j), fwd.dperiod[j],
                std::max(1e-4 * std::abs(fwd.dperiod[j]), 1e-5 * fwd.cycle.period_ms / std::abs(fwd.report.parameter_values[j])))
        << drawn[j];
}

// `job` in mode steady_cycle is refused with one line containing each of `says`; in mode auto
// it differentiates the run instead, with the same line as its note.
void refused_then_transient(const model::OdeModel& m, sensitivity::SensitivityJob job, const std::vector<std::string>& says) {
  job.mode = sensitivity::Mode::SteadyCycle;
  try {
    sensitivity::run_sensitivity_job(m, m.parameters().values(), job);
    ADD_FAILURE() << "a steady cycle was differentiated";
  } catch (const NoSteadyCycle& e) {
    const std::string msg = e.what();
    for (const auto& s : says) EXPECT_NE(msg.find(s), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
  job.mode = sensitivity::Mode::Auto;
  std::string note;
  const auto out = sensitivity::run_sensitivity_job(m, m.parameters().values(), job, [&](const std::string& s) { note = s; });
  EXPECT_EQ(out.mode, sensitivity::Mode::Transient);
  EXPECT_NE(note.find(says.front()), std::string::npos) << note;
  EXPECT_EQ(out.note, note);
}

// A job for `parameter`: the transient mode's run [discard_ms, t_end_ms], the cycle's transient
// and a period window of 1 s.
sensitivity::SensitivityJob job_for(const std::string& parameter, double t_end_ms, double discard_ms, double transient_ms) {
  sensitivity::SensitivityJob job;
  job.options = tight_options({parameter}, 1e-8);
  job.options.t_end_ms = t_end_ms;
  job.options.discard_ms = discard_ms;
  job.floquet_options.transient_ms = transient_ms;
  job.floquet_options.max_period_ms = 1000;
  return job;
}

TEST(CycleSensitivity, SpikingOrbitThatDoesNotCloseSaysSoNamingTheMeasure) {
  auto m = make("type = \"single_joint\"\nleg = \"middle\"\njoint = \"fti\"\n");
  refused_then_transient(*m, job_for("middle.fti.cpg_flx.g_app", 2000, 500, 3000),
                         {"does not close", "cycle-to-cycle period spread", "return residual"});
}

// A joint forced by a switch schedule has no free cycle.
TEST(CycleSensitivity, ForcedJointIsRefusedAndAutoDifferentiatesTheRun) {
  auto m = make("type = \"mechanical_joint\"\nleg = \"middle\"\njoint = \"fti\"\nstart_phase = \"flexion\"\n");
  refused_then_transient(*m, job_for("middle.fti.b_v", 3000, 1000, 1500), {"forced by the clock"});
}

// A parameter the model does not have is an error in every mode, not a reason to fall back.
TEST(CycleSensitivity, UnknownParameterIsAnErrorInAutoMode) {
  auto m = make("type = \"single_joint\"\nleg = \"middle\"\njoint = \"fti\"\nmotoneuron = \"rate\"\n");
  sensitivity::SensitivityJob job;
  job.options = tight_options({"middle.fti.no_such"}, 1e-8);
  std::string note;
  EXPECT_THROW(sensitivity::run_sensitivity_job(*m, m->parameters().values(), job, [&](const std::string& s) { note = s; }),
               Error);
  EXPECT_EQ(note, "");
}

// The forward runs go in chunks of parameters on threads: the numbers depend on the chunks
// only, so one thread and two give the same bits.
TEST(CycleSensitivity, ChunksOnTwoThreadsGiveTheSameBitsAsOnOne) {
  auto m = make("type = \"single_joint\"\nleg = \"middle\"\njoint = \"fti\"\nmotoneuron = \"rate\"\n");
  CycleSensitivityOptions co = default_cycle_options(*m);
  co.shooting.transient_ms = 3000;
  co.shooting.max_period_ms = 1000;
  auto opt = tight_options({"middle.fti.cpg_ext.g_app", "middle.fti.cpg_flx.g_app", "middle.fti.b_v", "cpg.g_L",
                                  "mn.rate.V_th", "middle.fti.l_F0", "muscle.b"},
                                 1e-8);
  opt.chunk_parameters = 3;
  opt.threads = 1;
  const CycleSensitivity one = analyse_cycle_sensitivities(*m, m->parameters().values(), opt, co);
  opt.threads = 2;
  const CycleSensitivity two = analyse_cycle_sensitivities(*m, m->parameters().values(), opt, co);
  ASSERT_EQ(one.report.absolute.rows(), two.report.absolute.rows());
  for (Eigen::Index f = 0; f < one.report.absolute.rows(); ++f)
    for (Eigen::Index j = 0; j < one.report.absolute.cols(); ++j) {
      const double a = one.report.absolute(f, j), b = two.report.absolute(f, j);
      EXPECT_TRUE(std::memcmp(&a, &b, sizeof a) == 0) << one.report.features[f].name << " by " << opt.parameters[j];
    }
  EXPECT_TRUE(one.dstate == two.dstate);
  EXPECT_TRUE(one.dperiod == two.dperiod);
}
