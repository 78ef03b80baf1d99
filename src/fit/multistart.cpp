#include "fit/multistart.hpp"

#include <omp.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "common/error.hpp"

namespace phasmid::fit {

MultistartResult multistart(const ResidualProblem& problem, const OptimizerOptions& options, const MultistartOptions& ms) {
  MultistartResult out;
  const size_t n = std::max<size_t>(ms.starts, 1);
  std::vector<std::vector<double>> starts = {problem.start()};
  if (n > 1) {
    auto more = start_points(ms.sampling, n - 1, problem.lower(), problem.upper(), ms.seed);
    starts.insert(starts.end(), more.begin(), more.end());
  }
  out.runs.resize(n);
  if (n == 1) {
    out.runs[0] = optimize(problem, starts[0], options);
    return out;
  }
  OptimizerOptions o = options;
  o.progress = false;  // one line for all starts instead
  const bool tty = options.progress && isatty(STDERR_FILENO);
  size_t done = 0;
  double best = std::numeric_limits<double>::infinity();
  const int threads = ms.threads > 0 ? ms.threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (long i = 0; i < static_cast<long>(n); ++i) {
    FitSummary s;
    try {
      s = optimize(problem, starts[i], o);
    } catch (const std::exception& e) {
      s.optimizer = o.method;
      s.x_start = s.x = starts[i];
      s.termination = "FAILURE";
      s.message = e.what();
      s.initial_cost = s.final_cost = NAN;
    }
    out.runs[i] = std::move(s);
#pragma omp critical(phasmid_multistart_progress)
    {
      ++done;
      if (out.runs[i].usable && out.runs[i].final_cost < best) best = out.runs[i].final_cost;
      if (tty) std::fprintf(stderr, "\r%s [%s] multistart %zu/%zu done, best cost %.6g   ", options.progress_label.c_str(),
                            o.method.c_str(), done, n, best);
    }
  }
  if (tty) std::fprintf(stderr, "\n");
  double b = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < n; ++i)
    if (out.runs[i].usable && out.runs[i].final_cost < b) {
      b = out.runs[i].final_cost;
      out.best = i;
    }
  return out;
}

}  // namespace phasmid::fit
