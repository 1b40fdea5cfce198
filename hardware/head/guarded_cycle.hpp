// One control cycle of a head driver, run by its PeriodicWorker: a LinkError
// (the port vanished, a write failed) marks the link down in the driver's
// health instead of ending the thread; the next cycle tries again. Any other
// exception (a reply the checks missed: a bug) is counted and named too,
// never let out of the thread, where it would end the program.
#pragma once

#include <exception>
#include <mutex>
#include <string>

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
  } catch (const std::exception& e) {
    std::lock_guard lock(healthMutex);
    ++health.cycleErrors;
    health.lastFault = std::string("driver cycle failed: ") + e.what();
  }
}

}  // namespace horopter::hw
