#pragma once
// The integration loop shared by the whole-system driver (Simulator::run) and the partitioned
// driver (run_partitioned): advance, take the root events, restart at the stops of the
// CommandSchedule, record outputs, show progress. The drivers differ only in what one advance
// is (the whole system to its next output time; the part furthest behind by one step) and in
// how they reach their states at events and outputs (the whole system has them; parts
// interpolate each other).
//
// A Driver provides:
//   bool finished(const CommandSchedule&)   every output recorded, the run is at t_end
//   double advance(CommandSchedule&)        one advance towards the next stop; the time reached
//   void handle_events(CommandSchedule&)    root events of that advance, trigger crossings
//                                           (which may add stops or restart at the event)
//   bool at_stop(const CommandSchedule&)    every integrator stands at the next stop
//   void restart(double tau, const std::vector<double>& dtau_dp, double next_stop)
//                                           restart at the stop tau (sensitivity jump dtau_dp),
//                                           integrating on to next_stop
//   void record_outputs()                   outputs up to the time reached
// Outputs at a stop are recorded after the restart there (the right-hand limits).
#include <chrono>
#include <string>
#include <vector>

#include "solver/command_schedule.hpp"
#include "solver/simulator.hpp"

namespace phasmid::solver {

// "<label>: t = T / T_END ms (P%[, N parts])" on stderr at most every 200 ms, when
// SolverOptions::progress is on and stderr is a terminal; finish() prints the 100 % line.
class ProgressLine {
 public:
  ProgressLine(const SolverOptions& options, double t_end, size_t parts);
  void update(double t);
  void finish();

 private:
  void print(double t, bool last);
  bool show_;
  std::string label_, parts_;
  double t_end_;
  std::chrono::steady_clock::time_point last_print_;
};

template <class Driver>
void run_loop(Driver& driver, CommandSchedule& schedule, ProgressLine& progress) {
  driver.record_outputs();
  while (!driver.finished(schedule)) {
    const double t = driver.advance(schedule);
    driver.handle_events(schedule);
    if (driver.at_stop(schedule) && !schedule.last_stop()) {
      const double tau = schedule.next_stop();
      const std::vector<double> dtau_dp = schedule.next_stop_jump();
      schedule.pass_stop();
      driver.restart(tau, dtau_dp, schedule.next_stop());
    }
    driver.record_outputs();
    progress.update(t);
  }
  progress.finish();
}

}  // namespace phasmid::solver
