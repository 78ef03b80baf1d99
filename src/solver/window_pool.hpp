#pragma once
// Worker threads for the windowed partitioned run (solver/partitioned_simulator.hpp): run(n,
// task) calls task(0) ... task(n-1), each once, on the calling thread and the workers, and
// returns when all have returned. Tasks are claimed one at a time from a shared ticket, so the
// caller never waits for a worker that has not claimed anything: on a machine whose other
// cores are busy the caller does all the work itself at almost no extra cost (an OpenMP team
// would wait at its barrier for every thread to be scheduled, and with the default spinning
// wait policy it was many times slower than the sequential run on a loaded machine).
// A worker spins briefly for the next call, then sleeps. The order in which tasks run is not
// fixed: tasks must not depend on each other.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace phasmid::solver {

class WindowPool {
 public:
  explicit WindowPool(int threads);  // threads - 1 workers (none for threads <= 1)
  ~WindowPool();
  WindowPool(const WindowPool&) = delete;
  WindowPool& operator=(const WindowPool&) = delete;

  void run(int n, const std::function<void(int)>& task);

 private:
  void work();
  bool claim_and_run(uint32_t generation);

  std::vector<std::thread> workers_;
  std::mutex m_;
  std::condition_variable wake_;
  bool stop_ = false;
  uint32_t generation_ = 0;
  static constexpr int kMaxTasks = 0xffff;
  std::atomic<uint64_t> ticket_{0};  // generation << 32 | task count << 16 | next task index
  std::atomic<int> done_{0};
  const std::function<void(int)>* task_ = nullptr;
};

}  // namespace phasmid::solver
