#include "fit/multistart.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "common/error.hpp"
#include "parallel/bytes.hpp"

namespace phasmid::fit {

std::string encode_summary(const FitSummary& s) {
  parallel::ByteWriter w;
  w.u64(s.converged).u64(s.usable).str(s.optimizer).str(s.termination).str(s.message);
  w.f64s(s.x_start).f64s(s.x).f64(s.initial_cost).f64(s.final_cost);
  w.u64(static_cast<std::uint64_t>(s.iterations)).u64(static_cast<std::uint64_t>(s.evaluations));
  w.u64(static_cast<std::uint64_t>(s.jacobian_evaluations)).u64(static_cast<std::uint64_t>(s.failed_evaluations));
  w.f64s(s.cost_history).strs(s.at_bound).f64(s.wall_seconds).str(s.report);
  return w.take();
}

FitSummary decode_summary(const std::string& bytes) {
  parallel::ByteReader r(bytes);
  FitSummary s;
  s.converged = r.u64() != 0;
  s.usable = r.u64() != 0;
  s.optimizer = r.str();
  s.termination = r.str();
  s.message = r.str();
  s.x_start = r.f64s();
  s.x = r.f64s();
  s.initial_cost = r.f64();
  s.final_cost = r.f64();
  s.iterations = static_cast<int>(r.u64());
  s.evaluations = static_cast<long>(r.u64());
  s.jacobian_evaluations = static_cast<long>(r.u64());
  s.failed_evaluations = static_cast<long>(r.u64());
  s.cost_history = r.f64s();
  s.at_bound = r.strs();
  s.wall_seconds = r.f64();
  s.report = r.str();
  return s;
}

MultistartResult multistart(const ResidualProblem& problem, const OptimizerOptions& options, const MultistartOptions& ms) {
  auto executor = parallel::make_openmp_executor(ms.threads);
  return multistart(problem, options, ms, *executor);
}

MultistartResult multistart(const ResidualProblem& problem, const OptimizerOptions& options, const MultistartOptions& ms,
                            parallel::Executor& executor) {
  MultistartResult out;
  const size_t n = std::max<size_t>(ms.starts, 1);
  std::vector<std::vector<double>> starts = {problem.start()};
  if (n > 1) {
    auto more = start_points(ms.sampling, n - 1, problem.lower(), problem.upper(), ms.seed);
    starts.insert(starts.end(), more.begin(), more.end());
  }
  out.runs.resize(n);
  if (n == 1 && !executor.distributed()) {  // a single fit shows the optimiser's own progress
    out.runs[0] = optimize(problem, starts[0], options);
    return out;
  }
  OptimizerOptions o = options;
  o.progress = false;  // one line for all starts instead
  const parallel::Evaluate evaluate = [&](const parallel::Task& t, int) {
    FitSummary s;
    try {
      s = optimize(problem, starts[t.id], o);
    } catch (const std::exception& e) {
      s.optimizer = o.method;
      s.x_start = s.x = starts[t.id];
      s.termination = "FAILURE";
      s.message = e.what();
      s.initial_cost = s.final_cost = NAN;
    }
    return encode_summary(s);
  };
  const bool tty = options.progress && isatty(STDERR_FILENO);
  size_t done = 0;
  double best = std::numeric_limits<double>::infinity();
  const parallel::Collect collect = [&](std::size_t i, std::string bytes) {
    out.runs[i] = decode_summary(bytes);
    ++done;
    if (out.runs[i].usable && out.runs[i].final_cost < best) best = out.runs[i].final_cost;
    if (tty) std::fprintf(stderr, "\r%s [%s] multistart %zu/%zu done, best cost %.6g   ", options.progress_label.c_str(),
                          o.method.c_str(), done, n, best);
  };
  std::vector<parallel::Task> tasks;
  for (size_t i = 0; i < n; ++i) tasks.push_back({i, {}});
  out.work = executor.run(tasks, evaluate, collect, [] { return true; });
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
