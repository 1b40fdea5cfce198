// What a head driver reports about its link, beside the measured angles.
#pragma once

#include "horopter/core/export.hpp"

#include <string>

namespace horopter::hw {

struct HOROPTER_API HeadHealth {
  bool linkUp = true;       // false after a LinkError or too many failed exchanges in a row
  long exchanges = 0;       // request/reply exchanges that succeeded
  long timeouts = 0;        // replies that never came (after retries)
  long corruptReplies = 0;  // bad checksum, short, garbage or values out of range
  long deviceErrors = 0;    // replies that carried an error from the device
  long cycleErrors = 0;     // exceptions a driver cycle threw (a bug; the thread goes on)
  std::string lastFault;    // empty until something went wrong
};

}  // namespace horopter::hw
