#pragma once
// One-line progress bar for long sweeps on a terminal: points done, failures, rate and time left.
#include <chrono>
#include <cstddef>
#include <string>

namespace phasmid::sweep {

class ProgressBar {
 public:
  // On a terminal (isatty(stderr)) a bar redrawn in place; into pipes and log files one plain
  // line per 10% of the points instead. `enabled` false: nothing.
  ProgressBar(std::size_t total, std::size_t already_done, bool enabled);
  // Called (serialised by the caller) after each point; redraws at most 5 times a second.
  void update(std::size_t done, std::size_t failed, bool force = false);
  void finish(std::size_t done, std::size_t failed);
  // "12.3 points/s, 1:02:03 left" text for given numbers (exposed for tests).
  static std::string format_eta(double seconds);

 private:
  std::size_t total_, start_done_;
  bool enabled_, tty_;
  bool drawn_ = false;
  std::size_t next_log_ = 0;  // non-terminal: the next point count that gets a line
  std::chrono::steady_clock::time_point t0_, last_;
};

}  // namespace phasmid::sweep
