// Waits, polling, for a condition that another thread (a driver, a
// simulated device) makes true: up to about 5 s, which a loaded machine
// needs, and no longer than it takes.
#pragma once

#include <chrono>
#include <thread>

namespace horopter::test {

template <typename F>
bool eventually(F condition) {
  using namespace std::chrono_literals;
  for (int i = 0; i < 500; ++i) {
    if (condition()) return true;
    std::this_thread::sleep_for(10ms);
  }
  return condition();
}

}  // namespace horopter::test
