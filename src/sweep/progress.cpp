#include "sweep/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace phasmid::sweep {

ProgressBar::ProgressBar(std::size_t total, std::size_t already_done, bool enabled)
    : total_(total), start_done_(already_done), enabled_(enabled), tty_(isatty(STDERR_FILENO)) {
  t0_ = last_ = std::chrono::steady_clock::now();
  next_log_ = already_done + std::max<std::size_t>(1, total / 10);
}

std::string ProgressBar::format_eta(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--";
  long s = std::lround(seconds);
  char buf[32];
  if (s >= 3600) std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  else std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  return buf;
}

void ProgressBar::update(std::size_t done, std::size_t failed, bool force) {
  if (!enabled_) return;
  auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - t0_).count();
  const double new_done = static_cast<double>(done - start_done_);
  const double rate = elapsed > 0 ? new_done / elapsed : 0.0;
  const double left = rate > 0 ? (total_ - done) / rate : NAN;
  if (!tty_) {
    if (done < next_log_ || done == start_done_) return;
    while (next_log_ <= done) next_log_ += std::max<std::size_t>(1, total_ / 10);
    std::fprintf(stderr, "sweep: %zu/%zu points", done, total_);
    if (failed) std::fprintf(stderr, " (%zu failed)", failed);
    std::fprintf(stderr, ", %.3g points/s, %s left\n", rate, format_eta(left).c_str());
    return;
  }
  if (!force && now - last_ < std::chrono::milliseconds(200)) return;
  last_ = now;
  constexpr int kWidth = 28;
  const int filled = total_ ? static_cast<int>(kWidth * done / total_) : kWidth;
  std::string bar(filled, '#');
  bar.resize(kWidth, '.');
  std::fprintf(stderr, "\rsweep [%s] %zu/%zu points", bar.c_str(), done, total_);
  if (failed) std::fprintf(stderr, " (%zu failed)", failed);
  if (rate >= 1) std::fprintf(stderr, "  %.1f points/s", rate);
  else if (rate > 0) std::fprintf(stderr, "  %.1f s/point", 1.0 / rate);
  std::fprintf(stderr, "  %s left   ", format_eta(left).c_str());
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::finish(std::size_t done, std::size_t failed) {
  if (!enabled_ || !tty_) return;
  update(done, failed, true);
  if (drawn_) std::fprintf(stderr, "\n");
}

}  // namespace phasmid::sweep
