// The C++ side of bench/bench_python.py: N runs of one scenario in a loop, as the Python module
// does them (Scenario::run with the config's [simulation] settings and t_end_ms), timed with
// the monotonic clock and in process CPU time. Prints one line:
// "runs N total_s S cpu_s C per_run_ms M features F".
//   bench_run_loop CONFIG [N=100] [T_END_MS=100]
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>

#include "common/error.hpp"
#include "config/config.hpp"

using namespace phasmid;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_run_loop CONFIG [N=100] [T_END_MS=100]\n");
    return 1;
  }
  const int n = argc > 2 ? std::atoi(argv[2]) : 100;
  try {
    config::Config cfg = config::load_config(argv[1]);
    auto scenario = config::build_scenario(cfg);
    config::SimulationSettings s = config::simulation_settings(cfg, scenario.get());
    if (argc > 3) s.t_end_ms = std::atof(argv[3]);
    else s.t_end_ms = 100.0;
    s.discard_ms = 0;  // as the Python loop must pass it: the config's 2000 ms is beyond the run
    const std::vector<double> p = scenario->parameters().values();
    size_t checksum = 0;
    const std::clock_t c0 = std::clock();
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < n; ++i) checksum += scenario->run(p, s)->features().size();
    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    std::printf("runs %d total_s %.6f cpu_s %.6f per_run_ms %.4f features %zu\n", n, total, cpu, 1e3 * total / n, checksum);
  } catch (const Error& e) {
    std::fprintf(stderr, "bench_run_loop: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
