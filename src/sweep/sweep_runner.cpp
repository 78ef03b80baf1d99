#include "sweep/sweep_runner.hpp"

#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <memory>
#include <optional>

#include "common/error.hpp"
#include "parallel/executor.hpp"
#include "io/output_lock.hpp"
#include "solver/simulator.hpp"
#include "sweep/progress.hpp"
#include "sweep/sweep_shard.hpp"

namespace phasmid::sweep {
namespace {

volatile std::sig_atomic_t g_stop_signal = 0;

extern "C" void on_stop_signal(int sig) {
  if (g_stop_signal) {  // second Ctrl-C: stop now (the journal holds every finished point)
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
  g_stop_signal = sig;
  parallel::abandon_in_flight();  // under MPI: rank 0 reports before mpirun ends the ranks
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


// What rank 0 (or the only process) needs to run the point loop and write the result.
struct MasterJob {
  const SweepInputs& in;
  const SweepOptions& opt;
  const model::ParameterSet& base_parameters;
  const std::vector<double>& base_p;
  std::chrono::steady_clock::time_point wall0;
};

// Opens (or resumes) the journal; on an MPI master, a refusal also ends the workers' wait.
// --resume of a finished file (no journal) first checks that the file is this sweep's.
std::shared_ptr<Journal> open_journal(const MasterJob& job, const std::string& path) {
  try {
    namespace fs = std::filesystem;
    if (!job.opt.resume && fs::exists(path))
      throw Error(path + ": journal of an unfinished sweep; pass --resume to continue it, or delete it to start over");
    if (job.opt.resume && !job.opt.shard.active() && !fs::exists(path) && fs::exists(job.opt.output))
      check_finished_sweep(job.opt.output, job.in);
    std::uint64_t fingerprint = sweep_fingerprint(job.in.resume_spec, job.in.spec);
    if (job.opt.shard.active()) fingerprint = shard_fingerprint(fingerprint, job.opt.shard);
    return std::make_shared<Journal>(path, fingerprint, job.in.spec.n_points, job.opt.resume, job.in.resume_spec);
  } catch (...) {
    parallel::release_workers();
    throw;
  }
}

// The sweep file, or with --shard the shard file (its points' journal lines, for `merge`).
void write_result(const MasterJob& job, std::vector<std::optional<PointResult>>& results) {
  const io::RunInfo info{job.in.resolved_config, job.opt.command};
  if (job.opt.shard.active()) {
    std::vector<std::string> records;
    for (std::size_t i = 0; i < results.size(); ++i)
      if (results[i]) records.push_back(encode_record(i, *results[i]));
    write_shard_h5(job.opt.output, job.in, job.opt.shard, records, info);
    return;
  }
  std::vector<PointResult> all;
  all.reserve(results.size());
  for (auto& r : results) all.push_back(std::move(*r));
  write_sweep_h5(job.opt.sweep_file.empty() ? job.opt.output : job.opt.sweep_file, job.in.spec, all,
                 job.base_parameters, job.base_p, info, job.in.resume_spec);
}

// The point loop on the master: hands the missing points (of its shard) to the executor,
// journals and stores each result as it arrives, shows progress; writes the file when done.
SweepOutcome run_master(const MasterJob& job, parallel::Executor& exec, const parallel::Evaluate& evaluate, SweepOutcome out) {
  const SweepOptions& opt = job.opt;
  const SweepSpec& spec = job.in.spec;
  // The output's lock before the journal is opened or truncated, held until the file is renamed
  // into place (taken by the verb already, or here for the Python module).
  std::optional<io::HeldOutputLock> lock;
  try {
    lock.emplace(opt.output);
  } catch (...) {
    parallel::release_workers();
    throw;
  }
  std::shared_ptr<Journal> journal = open_journal(job, out.journal);
  std::vector<std::optional<PointResult>> results(spec.n_points);
  for (auto& [i, r] : journal->recovered()) results[i] = r;
  out.n_recovered = journal->recovered().size();
  out.n_points = 0;
  std::vector<parallel::Task> pending;
  for (std::size_t i = 0; i < spec.n_points; ++i) {
    if (!opt.shard.owns(i)) continue;
    ++out.n_points;
    if (!results[i]) pending.push_back({i, {}});
    else if (results[i]->status != "ok") ++out.n_failed;
  }

  SignalGuard signals(opt.handle_signals);
  ProgressBar bar(out.n_points, out.n_recovered, opt.progress);
  long started = 0;
  std::size_t done = out.n_recovered;
  bar.update(done, out.n_failed, true);
  const parallel::KeepGoing keep_going = [&] {
    return !g_stop_signal && !(opt.stop_after >= 0 && started++ >= opt.stop_after);
  };
  const parallel::Collect collect = [&](std::size_t i, std::string line) {
    PointResult r;
    std::size_t back_index = 0;
    if (!decode_record(line, back_index, r) || back_index != i) throw Error("internal: journal record does not round-trip");
    journal->append_line(line);
    if (r.status != "ok") ++out.n_failed;
    results[i] = std::move(r);
    ++out.n_computed;
    bar.update(++done, out.n_failed);
  };
  out.work = exec.run(pending, evaluate, collect, keep_going);
  bar.finish(done, out.n_failed);
  out.signal = g_stop_signal;
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - job.wall0).count();
  if (done < out.n_points) {
    journal->sync();
    return out;
  }
  write_result(job, results);
  if (opt.keep_journal) out.kept_journal = journal;
  else journal->close_and_remove();
  out.complete = true;
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - job.wall0).count();
  return out;
}

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
  std::unique_ptr<parallel::Executor> exec = parallel::make_executor(opt.threads);
  out.threads = exec->slots();
  out.executor = exec->describe();
  out.distributed = exec->distributed();
  // One scenario per evaluation slot and option combination, built serially: slots share
  // nothing but read-only inputs.
  std::vector<std::vector<std::unique_ptr<scenario::Scenario>>> models(exec->slots());
  for (auto& per_slot : models)
    for (std::size_t c = 0; c < spec.n_combos; ++c) per_slot.push_back(in.make(c));
  scenario::RunSettings so = in.settings;
  so.solver.progress = false;
  // A point's result travels as its journal line (hex floats are exact; strings are normalised
  // to valid UTF-8), so the master stores exactly what a resumed sweep reads back.
  const parallel::Evaluate evaluate = [&](const parallel::Task& t, int slot) {
    const std::size_t c = spec.combo_of(t.id);
    return encode_record(t.id, evaluate_point(*models[slot][c], combo_p[c], combo_swept[c], spec, t.id, so));
  };
  if (!exec->is_master()) {  // an MPI worker: evaluate what rank 0 hands out, write nothing
    SignalGuard signals(opt.handle_signals);  // a Ctrl-C is rank 0's to report: serve until it says stop
    exec->run({}, evaluate, {}, {});
    out.worker = true;
    return out;
  }

  return run_master({in, opt, base_scenario->parameters(), base_p, wall0}, *exec, evaluate, std::move(out));
}

}  // namespace phasmid::sweep
