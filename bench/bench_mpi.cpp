// What the MPI master/worker layer costs and how it would scale (bench/bench_mpi.sh runs it;
// docs/performance.md "Threads, sweeps and MPI").
//   mpirun -np 3 bench_mpi master [TASKS [SLOTS]]  tasks/s through the master with a trivial
//                                           evaluator, SLOTS (8) tasks in flight per worker
//   bench_mpi costs CONFIG MASTER_US        runs CONFIG's sweep on one thread (per-point costs),
//                                           then projects the parallel efficiency at 64/256/1024
//                                           ranks from those costs and the master's cost per task
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <queue>
#include <string>
#include <vector>

#include "config/sweep_inputs.hpp"
#include "parallel/executor.hpp"
#include "parallel/session.hpp"
#include "sweep/sweep_runner.hpp"

using namespace phasmid;

namespace {

// Each worker keeps `slots` tasks in flight, so the master always has results waiting and the
// rate is what the master can handle, not the round-trip latency of one task.
int master_throughput(std::size_t n_tasks, int slots) {
  auto exec = parallel::make_executor(slots);
  std::vector<parallel::Task> tasks;
  for (std::size_t i = 0; i < n_tasks; ++i) tasks.push_back({i, {}});
  const std::string record(200, 'x');  // about a sweep point's journal line
  std::size_t received = 0;
  const auto t0 = std::chrono::steady_clock::now();
  exec->run(tasks, [&](const parallel::Task&, int) { return record; }, [&](std::size_t, std::string) { ++received; },
            [] { return true; });
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (exec->is_master())
    std::printf("master: %zu tasks through %s in %.3f s: %.0f tasks/s, %.1f us per task\n", received,
                exec->describe().c_str(), s, received / s, 1e6 * s / received);
  return 0;
}

// splitmix64: a deterministic resampling of the measured costs.
std::uint64_t splitmix(std::uint64_t& x) {
  std::uint64_t z = (x += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// Dynamic master/worker schedule of n tasks on ranks-1 workers: a worker gets its next task
// when the master has handled its result; the master handles one result at a time, master_s
// each. Returns the makespan.
double makespan(const std::vector<double>& costs, std::size_t n, int ranks, double master_s) {
  std::uint64_t seed = 1;
  using Ev = std::pair<double, int>;
  std::priority_queue<Ev, std::vector<Ev>, std::greater<Ev>> running;
  std::size_t next = 0;
  auto draw = [&] { return costs[splitmix(seed) % costs.size()]; };
  for (int w = 1; w < ranks && next < n; ++w, ++next) running.push({draw(), w});
  double master_free = 0;
  while (!running.empty()) {
    auto [t, w] = running.top();
    running.pop();
    master_free = std::max(master_free, t) + master_s;
    if (next < n) {
      running.push({master_free + draw(), w});
      ++next;
    }
  }
  return master_free;
}

int costs_and_projection(const std::string& config, double master_us) {
  config::Config cfg = config::load_config(config);
  sweep::SweepOptions o;
  o.output = (std::filesystem::temp_directory_path() / "phasmid_bench_mpi.h5").string();
  o.threads = 1;
  o.progress = false;
  std::filesystem::remove(o.output);
  sweep::SweepOutcome r = sweep::run_sweep(config::sweep_inputs(cfg, {}), o);
  std::filesystem::remove(o.output);
  std::vector<double> c = r.work.at(0).task_seconds;
  std::sort(c.begin(), c.end());
  double sum = 0;
  for (double x : c) sum += x;
  std::printf("one thread: %zu points in %.2f s; per point min %.2f s, median %.2f s, max %.2f s, mean %.2f s\n",
              c.size(), r.wall_seconds, c.front(), c[c.size() / 2], c.back(), sum / c.size());
  std::printf("projected parallel efficiency (work / (ranks x makespan); rank 0 is the master, %.1f us per task):\n",
              master_us);
  for (std::size_t n : {2000, 20000}) {
    std::printf("  %6zu points:", n);
    for (int ranks : {64, 256, 1024}) {
      std::uint64_t seed = 1;
      double work = 0;
      for (std::size_t i = 0; i < n; ++i) work += c[splitmix(seed) % c.size()];
      const double t = makespan(c, n, ranks, master_us * 1e-6);
      std::printf("  %4d ranks %5.1f %%", ranks, 100.0 * work / (ranks * t));
    }
    std::printf("\n");
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  parallel::Session mpi(argc, argv);
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "master")
    return master_throughput(argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 20000, argc > 3 ? std::atoi(argv[3]) : 8);
  if (mode == "costs" && argc > 3) return costs_and_projection(argv[2], std::atof(argv[3]));
  std::fprintf(stderr, "usage: mpirun -np N bench_mpi master [TASKS [SLOTS]] | bench_mpi costs CONFIG MASTER_US\n");
  return 1;
}
