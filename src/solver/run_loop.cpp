#include "solver/run_loop.hpp"

#include <unistd.h>

#include <cstdio>

#include "solver/interrupt.hpp"

namespace phasmid::solver {

ProgressLine::ProgressLine(const SolverOptions& options, double t_end, size_t parts)
    : show_(options.progress && isatty(STDERR_FILENO)),
      label_(options.progress_label),
      parts_(parts > 1 ? ", " + std::to_string(parts) + " parts" : ""),
      t_end_(t_end),
      last_print_(std::chrono::steady_clock::now()) {}

void ProgressLine::update(double t) {
  if (interrupt_requested()) throw Interrupted("interrupted at t = " + std::to_string(t) + " ms");
  if (!show_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_print_ <= std::chrono::milliseconds(200)) return;
  print(t, false);
  last_print_ = now;
}

void ProgressLine::finish() {
  if (show_) print(t_end_, true);
}

void ProgressLine::print(double t, bool last) {
  std::fprintf(stderr, "\r%s: t = %.0f / %.0f ms (%3.0f%%%s)%s", label_.c_str(), t, t_end_, 100.0 * t / t_end_,
               parts_.c_str(), last ? "\n" : "");
}

}  // namespace phasmid::solver
