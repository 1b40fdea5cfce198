// The PTU ASCII command set: see include/horopter/hardware/ptu_protocol.hpp.
#include "horopter/hardware/ptu_protocol.hpp"

#include <charconv>
#include <cmath>
#include <numbers>

#include "horopter/core/error.hpp"

namespace horopter::hw::ptu {

namespace {

char letter(Axis axis) {
  return axis == Axis::kPan ? 'P' : 'T';
}

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(b, e - b + 1));
}

// The text as it can be shown in a message: control bytes become '?'.
std::string printable(std::string_view s) {
  std::string shown;
  for (char c : s)
    shown += (c >= 0x20 && c < 0x7F) ? c : '?';
  return shown;
}

}  // namespace

std::string setPosition(Axis axis, long positions) {
  return std::string{letter(axis), 'P'} + std::to_string(positions) + " ";
}
std::string queryPosition(Axis axis) {
  return std::string{letter(axis), 'P', ' '};
}
std::string setSpeed(Axis axis, long positionsPerSecond) {
  return std::string{letter(axis), 'S'} + std::to_string(positionsPerSecond) + " ";
}
std::string querySpeed(Axis axis) {
  return std::string{letter(axis), 'S', ' '};
}
std::string queryResolution(Axis axis) {
  return std::string{letter(axis), 'R', ' '};
}
std::string queryMinPosition(Axis axis) {
  return std::string{letter(axis), 'N', ' '};
}
std::string queryMaxPosition(Axis axis) {
  return std::string{letter(axis), 'X', ' '};
}
std::string halt() {
  return "H ";
}
std::string await() {
  return "A ";
}
std::string terseFeedback() {
  return "FT ";
}
std::string echoOff() {
  return "ED ";
}
std::string independentControl() {
  return "CI ";
}

std::optional<std::string> takeLine(std::string& buffer) {
  while (true) {
    const auto end = buffer.find_first_of("\r\n");
    if (end == std::string::npos) return std::nullopt;
    std::string line = buffer.substr(0, end);
    buffer.erase(0, end + 1);
    if (!trim(line).empty()) return line;
  }
}

Reply parseReply(std::string_view line) {
  const std::string t = trim(line);
  if (t.empty()) throw Error("empty PTU reply");
  Reply r;
  if (t[0] == '*') {
    r.kind = ReplyKind::kOk;
    r.text = trim(std::string_view(t).substr(1));
    return r;
  }
  if (t[0] == '!') {
    const std::string rest = trim(std::string_view(t).substr(1));
    if (rest == "P" || rest == "T") {
      r.kind = ReplyKind::kLimitHit;
    } else {
      r.kind = ReplyKind::kError;
    }
    r.text = rest;
    return r;
  }
  throw Error("malformed PTU reply '" + printable(t) + "': expected '*' or '!' first");
}

double parseNumber(const Reply& reply) {
  if (reply.kind != ReplyKind::kOk) throw Error("PTU query failed: " + reply.text);
  double v = 0;
  const char* b = reply.text.data();
  const char* e = b + reply.text.size();
  const auto [ptr, ec] = std::from_chars(b, e, v);
  if (ec != std::errc() || ptr != e || reply.text.empty())
    throw Error("PTU reply '" + printable(reply.text) + "' is not a number");
  // from_chars reads "inf" and "nan"; no PTU quantity is either.
  if (!std::isfinite(v)) throw Error("PTU reply '" + printable(reply.text) + "' is not finite");
  return v;
}

long parseInteger(const Reply& reply) {
  const double v = parseNumber(reply);
  if (v != std::floor(v))
    throw Error("PTU reply '" + printable(reply.text) + "' is not an integer");
  // Positions and speeds fit 32 bits; a bigger value is garbage (and its cast
  // to long could be undefined).
  if (v < -2147483648.0 || v > 2147483647.0)
    throw Error("PTU reply '" + printable(reply.text) + "' is out of range (more than 32 bits)");
  return static_cast<long>(v);
}

double arcSecondsToRadians(double arcSeconds) {
  return arcSeconds / 3600.0 * std::numbers::pi / 180.0;
}

}  // namespace horopter::hw::ptu
