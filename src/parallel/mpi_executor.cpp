// MPI master/worker executor (see executor.hpp). Protocol, all on MPI_COMM_WORLD between rank
// 0 and each worker (MPI keeps the order of messages between two ranks):
//   worker -> master  kReady   u64 slots                        once per run()
//   master -> worker  kTask    u64 id, bytes input              one per free slot
//   worker -> master  kResult  u64 id, f64 seconds, u64 ok, bytes result (or error text)
//   master -> worker  kStop    (empty)                          when nothing is in flight
// Waiting ranks poll (MPI_Iprobe) with a growing sleep instead of blocking in MPI_Recv, which
// in Open MPI spins: a master or a worker's communication thread then costs no core that an
// evaluation could use, even with more ranks than cores.
#include "parallel/executor.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>

#include "common/error.hpp"
#include "parallel/bytes.hpp"
#include "parallel/session.hpp"

#include <csignal>

namespace phasmid::parallel {
namespace {
volatile std::sig_atomic_t g_abandon = 0;
}
void abandon_in_flight() { g_abandon = 1; }
}  // namespace phasmid::parallel

#ifdef PHASMID_WITH_MPI
#include <mpi.h>

namespace phasmid::parallel {
namespace {
bool g_released = false;
enum Tag : int { kReady = 1, kTask = 2, kResult = 3, kStop = 4 };

// Sleeps between polls: 20 us doubling up to 2 ms; reset after each message.
struct Backoff {
  std::chrono::microseconds wait{20};
  void sleep() {
    std::this_thread::sleep_for(wait);
    wait = std::min(wait * 2, std::chrono::microseconds(2000));
  }
  void reset() { wait = std::chrono::microseconds(20); }
};

void send(int to, Tag tag, const std::string& bytes) {
  MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD);
}

// A message from `from` (or any rank) if one is waiting.
bool try_receive(int from, int& source, int& tag, std::string& bytes) {
  int flag = 0;
  MPI_Status st;
  MPI_Iprobe(from, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
  if (!flag) return false;
  int n = 0;
  MPI_Get_count(&st, MPI_BYTE, &n);
  bytes.assign(static_cast<std::size_t>(n), '\0');
  MPI_Recv(bytes.data(), n, MPI_BYTE, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  source = st.MPI_SOURCE;
  tag = st.MPI_TAG;
  return true;
}

class MpiExecutor final : public Executor {
 public:
  explicit MpiExecutor(int threads) : threads_(std::max(1, threads)) {}
  int slots() const override { return rank() == 0 ? 0 : threads_; }
  bool is_master() const override { return rank() == 0; }
  bool distributed() const override { return true; }
  std::string describe() const override {
    return std::to_string(size()) + " ranks: " + std::to_string(size() - 1) + " worker" + (size() == 2 ? "" : "s") +
           " x " + std::to_string(threads_) + " thread" + (threads_ == 1 ? "" : "s");
  }
  std::vector<WorkerStats> run(const std::vector<Task>& tasks, const Evaluate& evaluate, const Collect& collect,
                               const KeepGoing& keep_going) override {
    if (rank() == 0) return master(tasks, collect, keep_going);
    worker(evaluate);
    return {};
  }

 private:
  std::vector<WorkerStats> master(const std::vector<Task>& tasks, const Collect& collect, const KeepGoing& keep_going);
  void worker(const Evaluate& evaluate) const;
  int threads_;
};

std::vector<WorkerStats> MpiExecutor::master(const std::vector<Task>& tasks, const Collect& collect,
                                             const KeepGoing& keep_going) {
  const int n = size();
  std::vector<WorkerStats> stats(n - 1);
  for (int w = 1; w < n; ++w) stats[w - 1].who = "rank " + std::to_string(w);
  std::vector<std::uint64_t> free_slots(n, 0);
  std::size_t next = 0, in_flight = 0;
  int ready = 0;
  bool handing = true;
  std::exception_ptr fatal;
  auto hand_out = [&](int w) {
    while (handing && free_slots[w] > 0 && next < tasks.size()) {
      if (!keep_going()) {
        handing = false;
        break;
      }
      send(w, kTask, ByteWriter().u64(tasks[next].id).str(tasks[next].input).take());
      ++next;
      --free_slots[w];
      ++in_flight;
    }
  };
  Backoff backoff;
  int source = 0, tag = 0;
  std::string bytes;
  while (ready < n - 1 || in_flight > 0) {
    if (!try_receive(MPI_ANY_SOURCE, source, tag, bytes)) {
      if (g_abandon) break;  // interrupted: the workers are stopped below, their points redone on --resume
      backoff.sleep();
      continue;
    }
    backoff.reset();
    ByteReader in(bytes);
    if (tag == kReady) {
      free_slots[source] = in.u64();
      ++ready;
    } else if (tag == kResult) {
      const std::size_t id = in.u64();
      const double seconds = in.f64();
      const bool ok = in.u64() != 0;
      std::string result = in.str();
      --in_flight;
      ++free_slots[source];
      WorkerStats& s = stats[source - 1];
      ++s.tasks;
      s.busy_seconds += seconds;
      s.task_seconds.push_back(seconds);
      try {
        if (!ok) throw Error("rank " + std::to_string(source) + ": task " + std::to_string(id) + ": " + result);
        if (!fatal) collect(id, std::move(result));
      } catch (...) {
        if (!fatal) fatal = std::current_exception();
        handing = false;
      }
    }
    hand_out(source);
  }
  for (int w = 1; w < n; ++w) send(w, kStop, {});
  if (g_abandon) g_released = true;  // the workers stop now; main() need not end the job
  if (fatal) std::rethrow_exception(fatal);
  return stats;
}

// The rank's main thread talks to the master; `threads_` evaluation threads take tasks from a
// local queue and leave results for the main thread to send.
void MpiExecutor::worker(const Evaluate& evaluate) const {
  std::mutex mu;
  std::condition_variable task_ready, result_ready;
  std::deque<Task> todo;
  std::deque<std::string> done;  // encoded kResult messages
  bool stop = false;
  auto evaluate_loop = [&](int slot) {
    for (;;) {
      Task t;
      {
        std::unique_lock<std::mutex> lock(mu);
        task_ready.wait(lock, [&] { return stop || !todo.empty(); });
        if (todo.empty()) return;
        t = std::move(todo.front());
        todo.pop_front();
      }
      const auto t0 = std::chrono::steady_clock::now();
      std::string result;
      bool ok = true;
      try {
        result = evaluate(t, slot);
      } catch (const std::exception& e) {
        ok = false;
        result = e.what();
      }
      const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::lock_guard<std::mutex> lock(mu);
      done.push_back(ByteWriter().u64(t.id).f64(sec).u64(ok).str(result).take());
      result_ready.notify_one();
    }
  };
  std::vector<std::thread> pool;
  for (int s = 0; s < threads_; ++s) pool.emplace_back(evaluate_loop, s);

  send(0, kReady, ByteWriter().u64(static_cast<std::uint64_t>(threads_)).take());
  Backoff backoff;
  int source = 0, tag = 0;
  std::string bytes;
  for (bool stopping = false; !stopping;) {
    std::deque<std::string> outgoing;
    {
      std::unique_lock<std::mutex> lock(mu);
      result_ready.wait_for(lock, backoff.wait, [&] { return !done.empty(); });
      outgoing.swap(done);
    }
    for (auto& m : outgoing) send(0, kResult, m);
    bool any = !outgoing.empty();
    while (try_receive(0, source, tag, bytes)) {
      any = true;
      std::lock_guard<std::mutex> lock(mu);
      if (tag == kStop) {
        stop = stopping = true;
        task_ready.notify_all();
        break;
      }
      ByteReader in(bytes);
      Task t;
      t.id = in.u64();
      t.input = in.str();
      todo.push_back(std::move(t));
      task_ready.notify_one();
    }
    if (any) backoff.reset();
    else backoff.wait = std::min(backoff.wait * 2, std::chrono::microseconds(2000));
  }
  for (auto& th : pool) th.join();
}

}  // namespace

std::unique_ptr<Executor> make_mpi_executor(int threads) { return std::make_unique<MpiExecutor>(threads); }

void release_workers() {
  if (rank() != 0) return;
  for (int w = 1; w < size(); ++w) send(w, kStop, {});
  g_released = true;
}

bool workers_released() { return g_released; }

}  // namespace phasmid::parallel

#else

namespace phasmid::parallel {
std::unique_ptr<Executor> make_mpi_executor(int) { throw Error("internal: MPI executor requested but MPI is not compiled in"); }
void release_workers() {}
bool workers_released() { return false; }
}  // namespace phasmid::parallel

#endif
