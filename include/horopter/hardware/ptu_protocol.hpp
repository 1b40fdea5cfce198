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

#include <optional>
#include <string>
#include <string_view>

namespace horopter::hw::ptu {

enum class Axis { kPan, kTilt };

std::string setPosition(Axis axis, long positions);        // "PP123 "
std::string queryPosition(Axis axis);                      // "PP "
std::string setSpeed(Axis axis, long positionsPerSecond);  // "PS1000 "
std::string querySpeed(Axis axis);                         // "PS "
std::string queryResolution(Axis axis);                    // "PR "
std::string queryMinPosition(Axis axis);                   // "PN "
std::string queryMaxPosition(Axis axis);                   // "PX "
std::string halt();                                        // "H "
std::string await();                                       // "A "
std::string terseFeedback();                               // "FT "
std::string echoOff();                                     // "ED "
std::string independentControl();                          // "CI "

enum class ReplyKind { kOk, kError, kLimitHit };

struct Reply {
  ReplyKind kind = ReplyKind::kOk;
  std::string text;  // the value of a query ("1000"), the error message, or "P"/"T"
};

// Takes one complete reply line (up to CR or LF, terminators dropped) off the
// front of `buffer`; nullopt while no terminator has arrived. Empty lines are
// skipped.
std::optional<std::string> takeLine(std::string& buffer);

// Parses a reply line; throws horopter::Error for a line that is neither
// "*..." nor "!..." (garbage on the line).
Reply parseReply(std::string_view line);

// The number in a query reply; throws horopter::Error if it is not one.
double parseNumber(const Reply& reply);
long parseInteger(const Reply& reply);

// Resolution in arc-seconds per position -> radians per position.
double arcSecondsToRadians(double arcSeconds);

}  // namespace horopter::hw::ptu
