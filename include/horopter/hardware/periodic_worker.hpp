// The control loop every driver of hardware/ runs on its own thread: one
// cycle now, then one every period, until stop(). A cycle that runs late does
// not make the next ones burst to catch up: the schedule restarts from now.
#pragma once

#include "horopter/core/export.hpp"

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace horopter::hw {

class HOROPTER_API PeriodicWorker {
 public:
  using Clock = std::chrono::steady_clock;

  PeriodicWorker() = default;
  ~PeriodicWorker() { stop(); }
  PeriodicWorker(const PeriodicWorker&) = delete;
  PeriodicWorker& operator=(const PeriodicWorker&) = delete;

  // Starts the thread; call at most once. `cycle` must not throw.
  void start(Clock::duration period, std::function<void()> cycle);
  // Runs the next cycle at once instead of at its time (an e-stop to send).
  void kick();
  // Stops the loop and joins the thread. Returns true the first time only,
  // so that the caller brings its device to rest once.
  bool stop();

 private:
  void loop(Clock::duration period);

  std::function<void()> cycle_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  bool kicked_ = false;
  std::thread thread_;
};

}  // namespace horopter::hw
