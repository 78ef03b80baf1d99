#include "solver/simulator.hpp"

#include <cvodes/cvodes.h>
#include <nvector/nvector_serial.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cmath>
#include <sstream>
#include <utility>

#include "common/error.hpp"
#include "solver/callback_data.hpp"
#include "solver/command_schedule.hpp"
#include "solver/cvodes_session.hpp"
#include "solver/dopri_session.hpp"
#include "solver/output_sink.hpp"
#include "solver/partitioned_simulator.hpp"
#include "solver/run_loop.hpp"

namespace phasmid::solver {

void compile_if_asked(model::OdeModelPart* part, const SolverOptions& options) {
  if (!options.compiled_rhs) return;
  std::string why = "this model kind has no compiled right-hand side";
  if (part && part->compile(&why)) return;
  static std::atomic<bool> warned{false};
  if (!warned.exchange(true))
    std::fprintf(stderr, "phasmid: warning: compiled_rhs: %s; the generic right-hand side runs instead\n", why.c_str());
}

using model::OdeModel;
using whole_system::CallbackData;

Simulator::Simulator(const OdeModel& model, SolverOptions options) : model_(model), options_(std::move(options)) {
  options_.validate();
}

OutputTimes OutputTimes::grid(double t_end, double dt) {
  if (!(dt > 0) || !(t_end > 0)) throw Error("output grid needs t_end > 0 and dt > 0");
  OutputTimes g;
  g.n_grid_ = static_cast<size_t>(std::floor(t_end / dt + 1e-9)) + 1;
  g.dt_ = dt;
  g.t_end_ = t_end;
  g.n_ = g.n_grid_ + (t_end - static_cast<double>(g.n_grid_ - 1) * dt > 1e-9 ? 1 : 0);
  return g;
}

std::vector<double> OutputTimes::to_vector() const {
  if (list_) return *list_;
  std::vector<double> t(n_);
  for (size_t k = 0; k < n_; ++k) t[k] = (*this)[k];
  return t;
}

std::vector<double> output_grid(double t_end, double dt) { return OutputTimes::grid(t_end, dt).to_vector(); }

namespace {

// The whole model as one CVODES system (the Driver of run_loop): each advance integrates to
// the next output time; triggers fire at once at their crossings.
class WholeSystem {
 public:
  WholeSystem(const OdeModel& model, const SolverOptions& options, const CommandSchedule& schedule,
              IntegratorSession& session, CallbackData& d, const OutputTimes& output_times,
              size_t n_caller_roots, SolveResult& res)
      : model_(model), options_(options), schedule_(schedule), session_(session), d_(d),
        output_times_(output_times), n_caller_roots_(n_caller_roots), res_(res), ns_(d.sens_params.size()),
        ydot_(d.n), rootsfound_(d.roots->size()) {
    if (output_times[0] <= 0.0) {
      record(0.0, false);
      k_out_ = 1;
    }
  }
  bool finished(const CommandSchedule&) const { return k_out_ == output_times_.size(); }
  double advance(CommandSchedule&);
  void handle_events(CommandSchedule& schedule);
  bool at_stop(const CommandSchedule& schedule) const {
    return flag_ == CV_TSTOP_RETURN && std::abs(t_ - schedule.next_stop()) < 1e-9;
  }
  void restart(double, const std::vector<double>& dtau_dp, double next_stop) {
    // The right-hand side changes here: restart from the current state. Sensitivities carry
    // over, plus a jump if the switch time moves with p.
    restart_here(dtau_dp);
    session_.set_stop_time(next_stop);
  }
  void record_outputs() {
    const double tout = output_times_[k_out_ < output_times_.size() ? k_out_ : 0];
    if (k_out_ < output_times_.size() && flag_ != kNone && std::abs(t_ - tout) < 1e-9 * std::max(1.0, std::abs(tout))) {
      record(tout, flag_ == CV_SUCCESS);  // events and restarts fetched them already
      ++k_out_;
    }
  }

 private:
  static constexpr int kNone = -1000;  // no advance yet
  void fire_triggers(CommandSchedule& schedule, std::vector<double>& dtau_now, bool& restart_now);
  void record_events();
  void record(double t, bool fetch_sens);
  void restart_here(const std::vector<double>& dtau_dp);
  std::vector<double*> sens_columns() const;

  const OdeModel& model_;
  const SolverOptions& options_;
  const CommandSchedule& schedule_;
  IntegratorSession& session_;
  CallbackData& d_;
  const OutputTimes& output_times_;
  const size_t n_caller_roots_;
  SolveResult& res_;
  const size_t ns_;
  std::vector<double> ydot_;
  std::vector<int> rootsfound_;
  size_t k_out_ = 0;
  double t_ = 0.0;
  int flag_ = kNone;
};

double WholeSystem::advance(CommandSchedule&) {
  flag_ = session_.advance(output_times_[k_out_], &t_, CV_NORMAL);
  if (flag_ < 0) {
    std::ostringstream os;
    os << session_.package() << " failed at t = " << t_ << " ms: " << session_.flag_name(flag_)
       << " " << failure_advice(options_, false);
    throw SolverError(os.str());
  }
  // Sensitivities are needed at events, at restarts and (if kept) at output times (record
  // fetches those).
  if (ns_ && (flag_ == CV_ROOT_RETURN || flag_ == CV_TSTOP_RETURN)) session_.fetch_sensitivities();
  return t_;
}

void WholeSystem::handle_events(CommandSchedule& schedule) {
  if (flag_ != CV_ROOT_RETURN) return;
  session_.root_info(rootsfound_.data());
  model_.rhs(t_, N_VGetArrayPointer(session_.y()), schedule.p().data(), ydot_.data());
  std::vector<double> dtau_now(ns_, 0.0);  // d tau / dp of commands triggered at this event
  bool restart_now = false;
  fire_triggers(schedule, dtau_now, restart_now);
  record_events();
  if (restart_now) {
    // A trigger set a command time to this very event: the right-hand side changes here;
    // s(t+) = s(t-) + (f(t-) - f(t+)) d t_event / dp. The restart is also needed without a
    // jump: at a root return CVODES' own sensitivities are at its internal time beyond the
    // root, the ones fetched at the root.
    restart_here(dtau_now);
  }
}

void WholeSystem::fire_triggers(CommandSchedule& schedule, std::vector<double>& dtau_now, bool& restart_now) {
  const double* y = N_VGetArrayPointer(session_.y());
  for (size_t k = 0; k < schedule.triggers().size(); ++k) {
    const int dir = rootsfound_[n_caller_roots_ + k];
    if (!dir || !schedule.fire(k, t_, dir, y, res_.commands)) continue;
    const model::CommandTrigger& tr = schedule.triggers()[k];
    const double when = t_ + tr.delay_ms;
    std::vector<double> dte;
    if (ns_) {
      std::vector<double> s_state(ns_);
      for (size_t j = 0; j < ns_; ++j) s_state[j] = NV_Ith_S(session_.s()[j], tr.state);
      dte = schedule.crossing_time_sensitivity(k, t_, ydot_[tr.state], s_state);
    }
    if (when <= t_ + 1e-9 * std::max(1.0, std::abs(t_))) {
      // The jump is applied after this event's sensitivities are recorded (they are s(t-)).
      restart_now = true;
      schedule.merge_jump(dtau_now, dte, k);
    } else if (when < schedule.t_end()) {
      // A later command: one more stop. The sensitivity is continuous at the event; it jumps
      // at tau with d tau / dp = d t_event / dp found here.
      if (schedule.add_command_time(when, dte, k) != CommandSchedule::Added::Existing)
        session_.set_stop_time(schedule.next_stop());
    }
  }
}

void WholeSystem::record_events() {
  const double* y = N_VGetArrayPointer(session_.y());
  const size_t n = d_.n;
  for (size_t r = 0; r < n_caller_roots_; ++r) {
    if (!rootsfound_[r]) continue;
    Event e;
    e.t = t_;
    e.root = r;
    e.direction = rootsfound_[r];
    e.y.assign(y, y + n);
    e.ydot = ydot_;
    if (ns_) {
      e.s.resize(n * ns_);
      for (size_t i = 0; i < n; ++i)
        for (size_t j = 0; j < ns_; ++j) e.s[i * ns_ + j] = NV_Ith_S(session_.s()[j], i);
    }
    res_.events.push_back(std::move(e));
  }
}

void WholeSystem::record(double t, bool fetch_sens) {
  if (options_.output_sink) {
    options_.output_sink->record(t, N_VGetArrayPointer(session_.y()), d_.n);
    res_.t.assign(1, t);
    return;
  }
  res_.t.push_back(t);
  res_.steps_at_output.push_back(session_.total_steps());
  const size_t n = d_.n;
  for (size_t i = 0; i < n; ++i) res_.y.push_back(NV_Ith_S(session_.y(), i));
  if (ns_ && options_.sensitivities_at_outputs) {
    if (fetch_sens) session_.fetch_sensitivities();
    for (size_t i = 0; i < n; ++i)
      for (size_t j = 0; j < ns_; ++j) res_.s.push_back(NV_Ith_S(session_.s()[j], i));
  }
}

void WholeSystem::restart_here(const std::vector<double>& dtau_dp) {
  if (ns_) schedule_.apply_jump(t_, dtau_dp, N_VGetArrayPointer(session_.y()), sens_columns());
  session_.restart(t_);
  ++res_.stats.restarts;
}

std::vector<double*> WholeSystem::sens_columns() const {
  std::vector<double*> s(ns_);
  for (size_t j = 0; j < ns_; ++j) s[j] = N_VGetArrayPointer(session_.s()[j]);
  return s;
}

}  // namespace

namespace {

// The whole model's integrator from y0: phasmid's Dormand-Prince for an explicit kind, else
// (and always with sensitivities, docs/sensitivity.md) CVODES BDF with its linear solver.
std::unique_ptr<IntegratorSession> make_session(SUNContext ctx, const OdeModel& model, const SolverOptions& options,
                                                CallbackData& d, const std::vector<double>& y0,
                                                const std::vector<size_t>& sens_params) {
  const size_t ns = sens_params.size();
  if (is_explicit_rk(options.integrator) && ns == 0)
    return std::make_unique<DopriSession>(ctx, options, y0.data(), d.n, whole_system::rhs_cb, &d);
  auto cv = std::make_unique<CvodesSession>(ctx, options, y0.data(), d.n, whole_system::rhs_cb, &d);
  whole_system::attach_linear_solver(*cv, d, model, options, y0, ns);
  if (ns > 0) whole_system::init_sensitivities(*cv, model, *d.p, sens_params);
  return cv;
}

}  // namespace

SolveResult Simulator::run(const std::vector<double>& p_given, const OutputTimes& output_times,
                           const std::vector<RootSpec>& roots, const std::vector<size_t>& sens_params) const {
  const SolveTimer timer;
  if (p_given.size() != model_.parameters().size()) throw Error("internal: parameter vector size mismatch");
  if (output_times.empty() || output_times.front() < 0) throw Error("output times must start at t >= 0");
  const size_t ns = sens_params.size();
  if (ns && options_.output_sink) throw Error("internal: an output sink takes no sensitivities");
  if (ns && !options_.atol_by_unit.empty())
    throw Error("solver option 'atol_by_unit' applies to runs without sensitivities");
  check_atol_units(model_, options_);
  const bool partition = options_.partitioning == Partitioning::On || options_.partitioning == Partitioning::Neurons;
  if (partition && ns == 0) {
    const model::ModelPartition parts = model_.partition(
        options_.partitioning == Partitioning::Neurons ? model::PartitionGrain::Neurons : model::PartitionGrain::Joints);
    if (parts.size() > 1) return run_partitioned(model_, parts, options_, p_given, output_times, roots);
  }
  CommandSchedule schedule(model_, p_given, output_times.back(), sens_params);
  const std::vector<RootSpec> all_roots = schedule.roots(roots);

  CallbackData d;
  d.model = &model_;
  d.p = &schedule.p();
  d.eq = model_.make_whole();
  if (d.eq) schedule.parameters().bind(d.eq.get());
  if (ns == 0) compile_if_asked(d.eq.get(), options_);
  d.roots = &all_roots;
  d.sens_params = sens_params;
  d.n = model_.num_states();
  d.init_scratch(schedule.parameters());

  SundialsContext ctx;
  const std::vector<double> y0 = model_.initial_state(schedule.p());
  const std::unique_ptr<IntegratorSession> session_owner = make_session(ctx.get(), model_, options_, d, y0, sens_params);
  IntegratorSession& session = *session_owner;
  if (!options_.atol_by_unit.empty()) {
    std::vector<size_t> all(d.n);
    for (size_t i = 0; i < d.n; ++i) all[i] = i;
    session.set_state_atol(state_atol(model_, options_, all));
  }
  std::vector<int> dirs;
  for (const auto& r : all_roots) dirs.push_back(r.direction);
  session.init_roots(dirs, whole_system::root_cb);
  session.set_stop_time(schedule.next_stop());

  SolveResult res;
  res.n_states = d.n;
  res.sens_params = sens_params;
  WholeSystem driver(model_, options_, schedule, session, d, output_times, roots.size(), res);
  ProgressLine progress(options_, schedule.t_end(), 1);
  run_loop(driver, schedule, progress);

  add_counters(res.stats, session.stats());
  res.stats.sens_rhs_evals = d.sens_evals;
  timer.stop(res.stats);
  return res;
}

}  // namespace phasmid::solver
