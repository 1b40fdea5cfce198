#include "horopter/hardware/periodic_worker.hpp"

#include <utility>

namespace horopter::hw {

void PeriodicWorker::start(Clock::duration period, std::function<void()> cycle) {
  cycle_ = std::move(cycle);
  thread_ = std::thread([this, period] { loop(period); });
}

void PeriodicWorker::kick() {
  {
    std::lock_guard lock(mutex_);
    kicked_ = true;
  }
  wake_.notify_all();
}

bool PeriodicWorker::stop() {
  {
    std::lock_guard lock(mutex_);
    if (stopping_) return false;
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
  return true;
}

void PeriodicWorker::loop(Clock::duration period) {
  auto next = Clock::now();
  while (true) {
    cycle_();
    next += period;
    std::unique_lock lock(mutex_);
    wake_.wait_until(lock, next, [this] { return stopping_ || kicked_; });
    if (stopping_) return;
    if (kicked_ || Clock::now() > next + period) next = Clock::now();
    kicked_ = false;
  }
}

}  // namespace horopter::hw
