#include "parallel/executor.hpp"

#include <omp.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <mutex>

#include "common/error.hpp"
#include "parallel/session.hpp"

namespace phasmid::parallel {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

class OpenMPExecutor final : public Executor {
 public:
  explicit OpenMPExecutor(int threads) : threads_(std::max(1, threads > 0 ? threads : omp_get_max_threads())) {}
  int slots() const override { return threads_; }
  bool is_master() const override { return true; }
  bool distributed() const override { return false; }
  std::string describe() const override { return std::to_string(threads_) + (threads_ == 1 ? " thread" : " threads"); }

  std::vector<WorkerStats> run(const std::vector<Task>& tasks, const Evaluate& evaluate, const Collect& collect,
                               const KeepGoing& keep_going) override {
    std::vector<WorkerStats> stats(threads_);
    for (int t = 0; t < threads_; ++t) stats[t].who = "thread " + std::to_string(t);
    std::mutex mu;  // serialises keep_going and collect
    std::atomic<bool> stop{false};
    std::exception_ptr fatal;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads_)
    for (long k = 0; k < static_cast<long>(tasks.size()); ++k) {
      if (stop.load()) continue;
      {
        std::lock_guard<std::mutex> lock(mu);
        if (stop.load() || !keep_going()) {
          stop = true;
          continue;
        }
      }
      const int t = omp_get_thread_num();
      const auto t0 = std::chrono::steady_clock::now();
      try {
        std::string result = evaluate(tasks[k], t);
        stats[t].task_seconds.push_back(seconds_since(t0));
        stats[t].busy_seconds += stats[t].task_seconds.back();
        ++stats[t].tasks;
        std::lock_guard<std::mutex> lock(mu);
        if (!fatal) collect(tasks[k].id, std::move(result));
      } catch (...) {
        std::lock_guard<std::mutex> lock(mu);
        if (!fatal) fatal = std::current_exception();
        stop = true;
      }
    }
    if (fatal) std::rethrow_exception(fatal);
    return stats;
  }

 private:
  int threads_;
};

}  // namespace

int bounded_threads(int threads) {
  // A negative count would silently mean the default: refused, as -j's own check does.
  if (threads < 0) throw Error("-j/--threads " + std::to_string(threads) + ": must be >= 0 (0: the default)");
  const int n = threads > 0 ? threads : omp_get_max_threads();
  if (n > kMaxThreads)
    throw Error((threads > 0 ? "-j/--threads " : "OMP_NUM_THREADS ") + std::to_string(n) + ": at most " +
                std::to_string(kMaxThreads) + " worker threads per process");
  return n;
}

std::unique_ptr<Executor> make_openmp_executor(int threads) {
  return std::make_unique<OpenMPExecutor>(bounded_threads(threads));
}

std::unique_ptr<Executor> make_executor(int threads) {
  if (size() == 1) return make_openmp_executor(threads);
  // An Error here (one rank's environment may differ) comes before the agreement: one line.
  const int n = threads > 0 ? bounded_threads(threads) : std::getenv("OMP_NUM_THREADS") ? bounded_threads(0) : 1;
  if (!agreed()) {  // the ranks' first MPI work: all passed their checks, or none works
    const Agreement a = agree("", 0);
    if (!a.all_ok) throw JobStopped{a.code, a.message, a.failed_rank};
  }
  return make_mpi_executor(n);
}

std::string format_work_summary(const std::vector<WorkerStats>& stats, const std::string& unit) {
  double total = 0;
  for (auto& s : stats) total += s.busy_seconds;
  std::string out;
  char line[160];
  for (auto& s : stats) {
    std::snprintf(line, sizeof line, "  %s: %zu %s, %.3g s busy (%.0f %%)\n", s.who.c_str(), s.tasks, unit.c_str(),
                  s.busy_seconds, total > 0 ? 100.0 * s.busy_seconds / total : 0.0);
    out += line;
  }
  return out;
}

}  // namespace phasmid::parallel
