#include "solver/window_pool.hpp"

#include <stdexcept>

namespace phasmid::solver {

namespace {
// Polls of the ticket before a worker sleeps: a few tens of microseconds, about one window's
// work of the three legs, so that back-to-back windows do not pay a wake-up each.
constexpr int kSpinPolls = 20000;
}  // namespace

WindowPool::WindowPool(int threads) {
  for (int k = 1; k < threads; ++k) workers_.emplace_back([this] { work(); });
}

WindowPool::~WindowPool() {
  {
    std::lock_guard<std::mutex> lock(m_);
    stop_ = true;
  }
  wake_.notify_all();
  for (auto& w : workers_) w.join();
}

// Claims tasks of `generation` until none is left; false if the ticket belongs to another one.
bool WindowPool::claim_and_run(uint32_t generation) {
  uint64_t t = ticket_.load(std::memory_order_acquire);
  for (;;) {
    if (static_cast<uint32_t>(t >> 32) != generation) return false;
    // The count is read from the ticket, not from a member: a worker leaving the previous call
    // would otherwise compare that call's exhausted ticket with the next call's larger count,
    // which the caller sets before it publishes the new generation, and claim a task twice.
    const uint32_t i = static_cast<uint32_t>(t & 0xffff), n = static_cast<uint32_t>((t >> 16) & 0xffff);
    if (i >= n) return true;
    if (!ticket_.compare_exchange_weak(t, t + 1, std::memory_order_acq_rel)) continue;
    (*task_)(static_cast<int>(i));
    done_.fetch_add(1, std::memory_order_release);
    t = ticket_.load(std::memory_order_acquire);
  }
}

void WindowPool::work() {
  uint32_t seen = 0;
  for (;;) {
    uint32_t g = static_cast<uint32_t>(ticket_.load(std::memory_order_acquire) >> 32);
    for (int s = 0; s < kSpinPolls && g == seen; ++s) {
      if (s % 64 == 63) std::this_thread::yield();  // a caller sharing this core runs first
      g = static_cast<uint32_t>(ticket_.load(std::memory_order_acquire) >> 32);
    }
    if (g == seen) {
      std::unique_lock<std::mutex> lock(m_);
      wake_.wait(lock, [&] { return stop_ || static_cast<uint32_t>(ticket_.load() >> 32) != seen; });
      if (stop_) return;
      g = static_cast<uint32_t>(ticket_.load() >> 32);
    }
    seen = g;
    claim_and_run(g);
  }
}

void WindowPool::run(int n, const std::function<void(int)>& task) {
  if (workers_.empty()) {
    for (int i = 0; i < n; ++i) task(i);
    return;
  }
  if (n > kMaxTasks) throw std::invalid_argument("WindowPool::run: more than 65535 tasks in one call");
  task_ = &task;
  done_.store(0, std::memory_order_relaxed);
  {
    std::lock_guard<std::mutex> lock(m_);
    ++generation_;
    ticket_.store(static_cast<uint64_t>(generation_) << 32 | static_cast<uint64_t>(n) << 16,
                  std::memory_order_release);
  }
  wake_.notify_all();
  claim_and_run(generation_);
  while (done_.load(std::memory_order_acquire) < n) std::this_thread::yield();
}

}  // namespace phasmid::solver
