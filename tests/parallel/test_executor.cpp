// The executor contract without MPI (the MPI side: tests/parallel/mpi_*.test.sh): every task is
// evaluated once and collected once with its own result; keep_going stops the hand-out;
// an exception from collect reaches the caller; bytes and fit summaries cross bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>

#include "common/error.hpp"
#include "parallel/bytes.hpp"
#include "parallel/executor.hpp"
#include "fit/multistart.hpp"

using namespace phasmid;

namespace {
std::vector<parallel::Task> tasks(std::size_t n) {
  std::vector<parallel::Task> t;
  for (std::size_t i = 0; i < n; ++i) t.push_back({i, "in" + std::to_string(i)});
  return t;
}
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
}  // namespace

TEST(Executor, EveryTaskOnceWithItsOwnResult) {
  auto exec = parallel::make_openmp_executor(3);
  ASSERT_EQ(exec->slots(), 3);
  std::map<std::size_t, std::string> got;
  auto stats = exec->run(
      tasks(200), [](const parallel::Task& t, int slot) { return t.input + "@" + std::to_string(t.id * t.id) + (slot < 3 ? "" : "!"); },
      [&](std::size_t id, std::string r) { EXPECT_TRUE(got.emplace(id, r).second) << "task " << id << " collected twice"; },
      [] { return true; });
  ASSERT_EQ(got.size(), 200u);
  for (std::size_t i = 0; i < 200; ++i) EXPECT_EQ(got[i], "in" + std::to_string(i) + "@" + std::to_string(i * i));
  std::size_t n = 0;
  for (auto& s : stats) {
    n += s.tasks;
    EXPECT_EQ(s.task_seconds.size(), s.tasks);
  }
  EXPECT_EQ(n, 200u);
}

TEST(Executor, KeepGoingStopsTheHandOut) {
  auto exec = parallel::make_openmp_executor(2);
  long asked = 0;
  std::size_t collected = 0;
  exec->run(tasks(50), [](const parallel::Task& t, int) { return std::to_string(t.id); },
            [&](std::size_t, std::string) { ++collected; }, [&] { return asked++ < 7; });
  EXPECT_EQ(collected, 7u);
}

TEST(Executor, CollectErrorReachesTheCaller) {
  auto exec = parallel::make_openmp_executor(2);
  EXPECT_THROW(exec->run(tasks(20), [](const parallel::Task& t, int) { return std::to_string(t.id); },
                         [](std::size_t id, std::string) {
                           if (id == 5) throw Error("journal full");
                         },
                         [] { return true; }),
               Error);
}

TEST(Bytes, RoundTripBitForBitAndRefuseTruncation) {
  const double odd[] = {-0.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::denorm_min(),
                        -std::numeric_limits<double>::infinity(), 0.1 + 0.2};
  std::vector<double> v(std::begin(odd), std::end(odd));
  std::string bytes = parallel::ByteWriter().u64(42).f64s(v).str(std::string("a\0b", 3)).strs({"x", ""}).take();
  parallel::ByteReader r(bytes);
  EXPECT_EQ(r.u64(), 42u);
  auto back = r.f64s();
  ASSERT_EQ(back.size(), v.size());
  for (std::size_t i = 0; i < v.size(); ++i) EXPECT_TRUE(same_bits(back[i], v[i])) << i;
  EXPECT_EQ(r.str(), std::string("a\0b", 3));
  EXPECT_EQ(r.strs(), (std::vector<std::string>{"x", ""}));
  std::string cut = bytes.substr(0, bytes.size() - 3);
  parallel::ByteReader t(cut);
  t.u64();
  t.f64s();
  t.str();
  EXPECT_THROW(t.strs(), Error);  // the last 3 bytes (inside the final string list) are missing
}

TEST(Bytes, FitSummaryRoundTrip) {
  fit::FitSummary s;
  s.converged = true;
  s.usable = true;
  s.optimizer = "ceres";
  s.termination = "CONVERGENCE";
  s.message = "Parameter tolerance reached.";
  s.x_start = {1.0 / 3.0, -2.5e-300};
  s.x = {0.1 + 0.2, std::nan("")};
  s.initial_cost = 4949.4;
  s.final_cost = 0.0679325;
  s.iterations = 6;
  s.evaluations = 21;
  s.jacobian_evaluations = 14;
  s.failed_evaluations = 1;
  s.cost_history = {4949.4, 12.5, 0.0679325};
  s.at_bound = {"middle.fti.b_v"};
  s.wall_seconds = 0.126736;
  s.report = "report\nlines";
  const fit::FitSummary b = fit::decode_summary(fit::encode_summary(s));
  EXPECT_EQ(fit::encode_summary(b), fit::encode_summary(s));
  EXPECT_TRUE(same_bits(b.x[0], s.x[0]));
  EXPECT_TRUE(std::isnan(b.x[1]));
  EXPECT_TRUE(same_bits(b.x_start[1], -2.5e-300));
  EXPECT_EQ(b.at_bound, s.at_bound);
  EXPECT_EQ(b.iterations, 6);
  EXPECT_EQ(b.failed_evaluations, 1);
  EXPECT_EQ(b.report, s.report);
  EXPECT_TRUE(b.converged && b.usable);
}
