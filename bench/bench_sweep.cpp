// Sweep throughput with 1 and 2 threads in one run, and the speed-up (target >= 1.8x on 2 cores).
//   bench_sweep [POINTS=16] [T_END_MS=1500]
// The workload is the single-joint FTi network (26 states, Section 3.1.2) on a Latin hypercube
// over the sensory drive and the viscosity. The baseline is the 1-thread run of the same binary.
#include <omp.h>
#include <time.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "config/sweep_inputs.hpp"
#include "io/h5_file.hpp"
#include "sweep/sweep_runner.hpp"

using namespace phasmid;

int main(int argc, char** argv) {
  const int points = argc > 1 ? std::atoi(argv[1]) : 16;
  const double t_end = argc > 2 ? std::atof(argv[2]) : 1500.0;
  char text[1024];
  std::snprintf(text, sizeof text, R"([model]
type = "single_joint"
leg = "middle"
joint = "fti"
[simulation]
rtol = 1e-8
atol = 1e-8
[sweep]
design = "lhs"
points = %d
seed = 1
t_end_ms = %g
discard_ms = %g
[[sweep.parameter]]
name = "middle.fti.sens_exc.g_app"
lower = 0.5
upper = 0.7
[[sweep.parameter]]
name = "middle.fti.b_v"
lower = 10
upper = 15
)", points, t_end, t_end / 3);
  config::Config cfg = config::parse_config(text, "bench_sweep");
  auto dir = std::filesystem::temp_directory_path() / ("phasmid_bench_sweep_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);

  std::string load;
  std::getline(std::ifstream("/proc/loadavg"), load);
  std::printf("bench_sweep: single-joint FTi network (26 states), %d LHS points, %g ms each; %d cores online; "
              "load average %s\n",
              points, t_end, static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN)), load.c_str());
  // On a shared machine the wall-clock speed-up is bounded by the cores we actually get: the
  // CPU time per point (flat if threads add no overhead) and the cores used (CPU / wall) show it.
  std::printf("%8s %10s %12s %10s %14s %11s\n", "threads", "wall [s]", "points/s", "speed-up", "cpu s/point",
              "cores used");
  auto cpu_now = [] {
    timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
  };
  double base = 0;
  std::vector<std::string> outs;
  for (int threads : {1, 2}) {
    sweep::SweepOptions o;
    o.output = (dir / ("t" + std::to_string(threads) + ".h5")).string();
    o.threads = threads;
    o.progress = false;
    const double cpu0 = cpu_now();
    sweep::SweepOutcome r = sweep::run_sweep(config::sweep_inputs(cfg, {}), o);
    const double cpu = cpu_now() - cpu0;
    if (threads == 1) base = r.wall_seconds;
    std::printf("%8d %10.2f %12.2f %9.2fx %14.3f %11.2f\n", threads, r.wall_seconds, r.n_points / r.wall_seconds,
                base / r.wall_seconds, cpu / r.n_points, cpu / r.wall_seconds);
    std::fflush(stdout);
    outs.push_back(o.output);
  }
  io::H5Reader a(outs[0]), b(outs[1]);
  bool same = a.read_strings("/sweep/status") == b.read_strings("/sweep/status");
  for (auto& n : a.children("/sweep/features")) {
    auto x = a.read_doubles("/sweep/features/" + n), y = b.read_doubles("/sweep/features/" + n);
    same = same && x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0;
  }
  std::printf("outputs of 1 and 2 threads bit-identical: %s\n", same ? "yes" : "NO");
  std::filesystem::remove_all(dir);
  return same ? 0 : 1;
}
