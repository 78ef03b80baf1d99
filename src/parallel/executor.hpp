#pragma once
// Runs independent tasks and hands their results to one collector (docs/cluster.md). A task is
// an identifier plus optional input bytes; evaluating it yields a result as bytes; the
// collector (journal, result table, progress) runs serially in one place. Two implementations:
//  - OpenMP threads in one process (dynamic schedule, one task per thread at a time);
//  - MPI master/worker, chosen when the job has more than one rank: rank 0 hands out tasks
//    and collects, the other ranks evaluate, each with `threads` evaluation threads (only the
//    rank's main thread calls MPI). A worker gets its next task when it returns a result;
//    identifiers travel in the payload, not in MPI tags.
// Every rank of an MPI job calls make_executor() and run() at the same points, in the same
// order (one run() per phase of work); on worker ranks run() serves until the master says the
// phase is over, and its task list, collector and keep_going are not used.
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace phasmid::parallel {

struct Task {
  std::size_t id = 0;
  std::string input;  // what the evaluator needs beyond the id (empty when every rank knows it)
};

// Evaluates a task on evaluation slot `slot` (0 .. slots()-1: per-slot state such as model
// copies is indexed by it). Should not throw: an exception stops the run and is rethrown by
// run() on the master (naming the rank on MPI).
using Evaluate = std::function<std::string(const Task& task, int slot)>;
// Receives a task's result on the master, one call at a time, in order of arrival. An
// exception stops handing out tasks; it is rethrown once the tasks in flight have returned.
using Collect = std::function<void(std::size_t id, std::string result)>;
// Asked (serially) before each task is handed out; false: hand out no more.
using KeepGoing = std::function<bool()>;

struct WorkerStats {
  std::string who;  // "rank 3" or "thread 1"
  std::size_t tasks = 0;
  double busy_seconds = 0;  // time spent evaluating
  std::vector<double> task_seconds;  // each task's evaluation time, in order of completion
};

class Executor {
 public:
  virtual ~Executor() = default;
  virtual int slots() const = 0;           // evaluation slots on this rank (0 on an MPI master)
  virtual bool is_master() const = 0;      // hands out tasks and collects results
  virtual bool distributed() const = 0;    // MPI with more than one rank
  virtual std::string describe() const = 0;  // "2 threads", "3 ranks: 2 workers x 1 thread"
  // Returns the per-worker work on the master (empty on workers).
  virtual std::vector<WorkerStats> run(const std::vector<Task>& tasks, const Evaluate& evaluate,
                                       const Collect& collect, const KeepGoing& keep_going) = 0;
};

// threads: evaluation threads per process or rank; 0 = OpenMP's default without MPI, and
// OMP_NUM_THREADS (else 1) per rank under MPI, so N ranks on a node do not each take all cores.
std::unique_ptr<Executor> make_executor(int threads);
// More threads than this (from -j or OMP_NUM_THREADS) is an Error: OpenMP cannot start them
// (a crash, not a message) and no machine phasmid runs on has that many cores per process.
inline constexpr int kMaxThreads = 256;
int bounded_threads(int threads);  // 0 -> OpenMP's default; an Error below 0 or above kMaxThreads

// One line per worker: "rank R: N tasks, S s busy (P %)", with the share of all busy time.
std::string format_work_summary(const std::vector<WorkerStats>& stats, const std::string& unit);

// On the MPI master after an error outside run(): tells every worker that the current phase is
// over, so that the job ends instead of waiting. Nothing without MPI or on workers.
void release_workers();
// Whether release_workers() was called: main() ends a failed job with abort_job() otherwise,
// since other ranks may be waiting for this one.
bool workers_released();

// From a signal handler (async-signal-safe): the MPI master stops handing out tasks and, instead
// of waiting for the tasks in flight, tells the workers to stop and returns at once. Open MPI's
// mpirun ends every rank soon after a Ctrl-C (SIGTERM, then SIGKILL): rank 0 must report and
// keep its journal before that; the points in flight are recomputed by --resume.
void abandon_in_flight();

// Implementations (executor.cpp, mpi_executor.cpp).
std::unique_ptr<Executor> make_openmp_executor(int threads);
std::unique_ptr<Executor> make_mpi_executor(int threads);

}  // namespace phasmid::parallel
