// What a head driver reports about its link, beside the measured angles.
#pragma once

#include "horopter/core/export.hpp"

#include <string>

namespace horopter::hw {

struct HOROPTER_API HeadHealth {
  bool linkUp = true;       // false after a LinkError or too many failed exchanges in a row
  long exchanges = 0;       // request/reply exchanges that succeeded
  long timeouts = 0;        // replies that never came (after retries)
  long corruptReplies = 0;  // replies with a bad checksum, short or garbage
  long deviceErrors = 0;    // replies that carried an error from the device
  std::string lastFault;    // empty until something went wrong
};

}  // namespace horopter::hw
