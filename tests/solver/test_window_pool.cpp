// The windowed run's worker pool (solver/window_pool.hpp): every call runs each of its n tasks
// exactly once, none of them after run() has returned, also when n changes from one call to
// the next (the windowed driver's n is the number of parts behind the window's end, which
// varies). A worker still leaving the previous call must not claim a task of the next one by
// the previous call's ticket, nor count a task twice.
#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include "solver/window_pool.hpp"

using phasmid::solver::WindowPool;

namespace {

struct Tally {
  std::vector<std::atomic<int>> runs;
  std::atomic<int> running{0};  // tasks inside their body
  explicit Tally(int n) : runs(n) {}
};

// Calls run() `calls` times with n cycling through `sizes`; returns the number of calls in
// which a task ran other than once, or ran on after run() returned.
int faulty_calls(WindowPool& pool, const std::vector<int>& sizes, int calls) {
  int faulty = 0;
  Tally tally(64);
  for (int c = 0; c < calls; ++c) {
    const int n = sizes[c % sizes.size()];
    for (int i = 0; i < n; ++i) tally.runs[i].store(0);
    pool.run(n, [&](int i) {
      tally.running.fetch_add(1);
      tally.runs[i].fetch_add(1);
      tally.running.fetch_sub(1);
    });
    bool ok = tally.running.load() == 0;
    for (int i = 0; i < n; ++i) ok = ok && tally.runs[i].load() == 1;
    if (!ok) ++faulty;
  }
  return faulty;
}

}  // namespace

TEST(WindowPool, EveryTaskOnceWhenTheCountChangesBetweenCalls) {
  WindowPool pool(2);
  // Short and long calls alternate: after a short call the worker is still reading the
  // ticket while the caller starts a longer one.
  EXPECT_EQ(faulty_calls(pool, {1, 9, 2, 9, 3, 9}, 200000), 0);
}

TEST(WindowPool, EveryTaskOnceWithAFixedCount) {
  WindowPool pool(3);
  EXPECT_EQ(faulty_calls(pool, {9}, 50000), 0);
}

TEST(WindowPool, WithoutWorkersTheCallerRunsEveryTaskInOrder) {
  WindowPool pool(1);
  std::vector<int> order;
  pool.run(5, [&](int i) { order.push_back(i); });
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3, 4}));
}
