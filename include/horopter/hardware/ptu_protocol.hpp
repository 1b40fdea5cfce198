// The FLIR (Directed Perception) pan-tilt unit ASCII command set, pure functions.
//
// Sources: FLIR PTU-D300 User's Manual v2.19 §4 "Command Reference" and the
// E Series Command Reference Manual (FLIR, 2014/2016), and the ROS driver
// flir_ptu_driver (ros-drivers/flir_ptu, driver.cpp) for the terse-mode usage.
//
//   Command   <letters><number><delim>   e.g. "PP-2500 " sets pan position
//   Query     <letters><delim>           e.g. "PP " asks the pan position
//   <delim>   a space or a carriage return (we send a space)
//   Replies   "*" (+ " <value>" for a query) on success, "! <message>" on a
//             failed command, "!P" / "!T" asynchronously when the pan / tilt
//             axis hits a limit; lines end with CR (LF tolerated)
//   Setup     FT (terse feedback: "* 1000", not "* Current Pan position is
//             1000"), ED (no echo), CI (independent position control)
//   Units     positions (steps) and positions/s; PR / TR give the
//             resolution in arc-seconds per position
//   Queries   PP TP position, PS TS speed, PR TR resolution, PN PX TN TX
//             factory position limits; H halt, A await (reply once the last
//             position command has been reached)
#pragma once

#include "horopter/core/export.hpp"

#include <optional>
#include <string>
#include <string_view>

namespace horopter::hw::ptu {

enum class Axis { kPan, kTilt };

HOROPTER_API std::string setPosition(Axis axis, long positions);        // "PP123 "
HOROPTER_API std::string queryPosition(Axis axis);                      // "PP "
HOROPTER_API std::string setSpeed(Axis axis, long positionsPerSecond);  // "PS1000 "
HOROPTER_API std::string querySpeed(Axis axis);                         // "PS "
HOROPTER_API std::string queryResolution(Axis axis);                    // "PR "
HOROPTER_API std::string queryMinPosition(Axis axis);                   // "PN "
HOROPTER_API std::string queryMaxPosition(Axis axis);                   // "PX "
HOROPTER_API std::string halt();                                        // "H "
HOROPTER_API std::string await();                                       // "A "
HOROPTER_API std::string terseFeedback();                               // "FT "
HOROPTER_API std::string echoOff();                                     // "ED "
HOROPTER_API std::string independentControl();                          // "CI "

enum class ReplyKind { kOk, kError, kLimitHit };

struct HOROPTER_API Reply {
  ReplyKind kind = ReplyKind::kOk;
  std::string text;  // the value of a query ("1000"), the error message, or "P"/"T"
};

// Takes one complete reply line (up to CR or LF, terminators dropped) off the
// front of `buffer`; nullopt while no terminator has arrived. Empty lines are
// skipped.
HOROPTER_API std::optional<std::string> takeLine(std::string& buffer);

// Parses a reply line; throws horopter::Error for a line that is neither
// "*..." nor "!..." (garbage on the line).
HOROPTER_API Reply parseReply(std::string_view line);

// The number in a query reply; throws horopter::Error if it is not one, or
// not finite ("inf", "nan"), or for an integer beyond 32 bits.
HOROPTER_API double parseNumber(const Reply& reply);
HOROPTER_API long parseInteger(const Reply& reply);

// Resolution in arc-seconds per position -> radians per position.
HOROPTER_API double arcSecondsToRadians(double arcSeconds);

}  // namespace horopter::hw::ptu
