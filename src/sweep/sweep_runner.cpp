#include "sweep/sweep_runner.hpp"

#include <omp.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <exception>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>

#include "common/error.hpp"
#include "solver/simulator.hpp"
#include "sweep/progress.hpp"

namespace phasmid::sweep {
namespace {

volatile std::sig_atomic_t g_stop_signal = 0;

extern "C" void on_stop_signal(int sig) {
  if (g_stop_signal) {  // second Ctrl-C: stop now (the journal holds every finished point)
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
  g_stop_signal = sig;
}

// Installs the handlers for the lifetime of a run and restores the previous ones.
struct SignalGuard {
  bool active;
  struct sigaction old_int {}, old_term {};
  explicit SignalGuard(bool on) : active(on) {
    g_stop_signal = 0;
    if (!active) return;
    struct sigaction sa {};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int);
    sigaction(SIGTERM, &sa, &old_term);
  }
  ~SignalGuard() {
    if (!active) return;
    sigaction(SIGINT, &old_int, nullptr);
    sigaction(SIGTERM, &old_term, nullptr);
  }
};

}  // namespace

std::string gait_class_of(const std::vector<features::Feature>& features) {
  for (const auto& f : features)
    if (f.name == "gait_class") {
      // The walking models' code (features::classify_gait): 2 tripod, 1 tetrapod, 0 irregular.
      if (!std::isfinite(f.value)) return "unclassified";
      return features::gait_class_name(static_cast<int>(std::lround(f.value)));
    }
  return "ok";
}

PointResult evaluate_point(const scenario::Scenario& scenario, const std::vector<double>& base_parameters,
                           const std::vector<std::size_t>& swept_indices, const SweepSpec& spec,
                           std::size_t point, const scenario::RunSettings& settings) {
  PointResult r;
  try {
    std::vector<double> p = base_parameters;
    for (std::size_t d = 0; d < swept_indices.size(); ++d) p[swept_indices[d]] = spec.at(point, d);
    scenario::RunSettings s = settings;
    s.t_end_ms = spec.t_end_ms;
    s.discard_ms = spec.discard_ms;
    r.features = scenario.evaluate_features(p, s);
    r.gait_class = gait_class_of(r.features);
  } catch (const std::exception& e) {  // SolverError, any phasmid::Error, or worse: recorded, not fatal
    r = PointResult{};
    r.status = e.what();
    if (r.status.empty() || r.status == "ok") r.status = "failed";
    r.gait_class = "failed";
  }
  return r;
}

SweepOutcome run_sweep(const SweepInputs& in, const SweepOptions& opt) {
  const auto wall0 = std::chrono::steady_clock::now();
  const SweepSpec& spec = in.spec;
  const std::string& resolved = in.resolved_config;
  // Per option combination: its base parameter vector and swept parameter indices.
  std::vector<std::vector<double>> combo_p;
  std::vector<std::vector<std::size_t>> combo_swept;
  std::unique_ptr<scenario::Scenario> base_scenario;
  for (std::size_t c = 0; c < spec.n_combos; ++c) {
    auto s = in.make(c);
    combo_p.push_back(s->parameters().values());
    std::vector<std::size_t> idx;
    for (auto& p : spec.parameters) idx.push_back(s->parameters().index(p.name));
    combo_swept.push_back(std::move(idx));
    if (c == 0) base_scenario = std::move(s);
  }
  const std::vector<double>& base_p = combo_p.front();

  SweepOutcome out;
  out.n_points = spec.n_points;
  out.output = opt.output;
  out.journal = Journal::path_for(opt.output);
  if (!opt.resume && std::filesystem::exists(out.journal))
    throw Error(out.journal + ": journal of an unfinished sweep; pass --resume to continue it, or delete it to start over");
  Journal journal(out.journal, sweep_fingerprint(resolved, spec), spec.n_points, opt.resume);

  std::vector<std::optional<PointResult>> results(spec.n_points);
  for (auto& [i, r] : journal.recovered()) results[i] = r;
  out.n_recovered = journal.recovered().size();
  std::vector<std::size_t> pending;
  for (std::size_t i = 0; i < spec.n_points; ++i)
    if (!results[i]) pending.push_back(i);
    else if (results[i]->status != "ok") ++out.n_failed;

  const int nthreads = std::max(1, opt.threads > 0 ? opt.threads : omp_get_max_threads());
  out.threads = nthreads;
  // One model per thread and option combination, built serially: threads share nothing but
  // read-only inputs.
  std::vector<std::vector<std::unique_ptr<scenario::Scenario>>> models(nthreads);
  for (auto& per_thread : models)
    for (std::size_t c = 0; c < spec.n_combos; ++c) per_thread.push_back(in.make(c));
  scenario::RunSettings so = in.settings;
  so.solver.progress = false;

  SignalGuard signals(opt.handle_signals);
  ProgressBar bar(spec.n_points, out.n_recovered, opt.progress);
  std::mutex mu;
  std::atomic<bool> stop{false};
  std::atomic<long> started{0};
  std::exception_ptr fatal;
  std::size_t done = out.n_recovered;
  bar.update(done, out.n_failed, true);

#pragma omp parallel for schedule(dynamic, 1) num_threads(nthreads)
  for (long k = 0; k < static_cast<long>(pending.size()); ++k) {
    if (stop.load() || g_stop_signal) continue;
    if (opt.stop_after >= 0 && started.fetch_add(1) >= opt.stop_after) {
      stop = true;
      continue;
    }
    const std::size_t i = pending[k];
    try {
      const std::size_t c = spec.combo_of(i);
      PointResult r = evaluate_point(*models[omp_get_thread_num()][c], combo_p[c], combo_swept[c], spec, i, so);
      // Keep exactly what the journal holds (hex floats are exact; strings are normalised to
      // valid UTF-8), so a resumed sweep assembles the very same values.
      const std::string line = encode_record(i, r);
      std::size_t back_index = 0;
      if (!decode_record(line, back_index, r) || back_index != i) throw Error("internal: journal record does not round-trip");
      journal.append_line(line);
      std::lock_guard<std::mutex> lock(mu);
      if (r.status != "ok") ++out.n_failed;
      results[i] = std::move(r);
      ++out.n_computed;
      ++done;
      bar.update(done, out.n_failed);
    } catch (...) {  // journal I/O failure: stop everything, report after the loop
      std::lock_guard<std::mutex> lock(mu);
      if (!fatal) fatal = std::current_exception();
      stop = true;
    }
  }
  bar.finish(done, out.n_failed);
  if (fatal) std::rethrow_exception(fatal);
  out.signal = g_stop_signal;
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  if (done < spec.n_points) {
    journal.sync();
    return out;
  }

  std::vector<PointResult> all;
  all.reserve(spec.n_points);
  for (auto& r : results) all.push_back(std::move(*r));
  write_sweep_h5(opt.output, spec, all, base_scenario->parameters(), base_p, {resolved, opt.command});
  journal.close_and_remove();
  out.complete = true;
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return out;
}

}  // namespace phasmid::sweep
