// One control cycle of a head driver, run by its PeriodicWorker: a LinkError
// (the port vanished, a write failed) marks the link down in the driver's
// health instead of ending the thread; the next cycle tries again.
#pragma once

#include <mutex>

#include "horopter/hardware/head_health.hpp"
#include "horopter/hardware/transport.hpp"

namespace horopter::hw {

template <typename Cycle>
void runGuardedCycle(Cycle&& cycle, std::mutex& healthMutex, HeadHealth& health) {
  try {
    cycle();
  } catch (const LinkError& e) {
    std::lock_guard lock(healthMutex);
    health.linkUp = false;
    health.lastFault = e.what();
  }
}

}  // namespace horopter::hw
