// FLIR PTU driver: see include/horopter/hardware/ptu_head.hpp.
#include "horopter/hardware/ptu_head.hpp"

#include <algorithm>
#include <cmath>

#include "head/guarded_cycle.hpp"

namespace horopter::hw {

namespace {
std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  const auto e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}
}  // namespace

PtuHead::PtuHead(std::unique_ptr<ByteTransport> transport, PtuHeadOptions options)
    : transport_(std::move(transport)), options_(options) {
  if (!transport_) throw Error("PtuHead needs a transport");
  if (std::abs(options_.panDirection) != 1 || std::abs(options_.tiltDirection) != 1)
    throw Error("pan/tilt direction must be +1 or -1");
  require(ptu::terseFeedback());
  require(ptu::echoOff());
  require(ptu::independentControl());
  panRes_ =
      ptu::arcSecondsToRadians(ptu::parseNumber(require(ptu::queryResolution(ptu::Axis::kPan))));
  tiltRes_ =
      ptu::arcSecondsToRadians(ptu::parseNumber(require(ptu::queryResolution(ptu::Axis::kTilt))));
  const double maxRes = ptu::arcSecondsToRadians(3600);  // coarser than 1 degree: nonsense
  if (!(panRes_ > 0 && panRes_ <= maxRes) || !(tiltRes_ > 0 && tiltRes_ <= maxRes))
    throw Error("the PTU reported a resolution outside (0, 3600] arc-seconds per position");
  const long pn = ptu::parseInteger(require(ptu::queryMinPosition(ptu::Axis::kPan)));
  const long px = ptu::parseInteger(require(ptu::queryMaxPosition(ptu::Axis::kPan)));
  const long tn = ptu::parseInteger(require(ptu::queryMinPosition(ptu::Axis::kTilt)));
  const long tx = ptu::parseInteger(require(ptu::queryMaxPosition(ptu::Axis::kTilt)));
  if (pn > px || tn > tx)
    throw Error("the PTU reported limits with min above max (pan " + std::to_string(pn) + ".." +
                std::to_string(px) + ", tilt " + std::to_string(tn) + ".." + std::to_string(tx) +
                ")");
  panMin_ = pn;
  panMax_ = px;
  tiltMin_ = tn;
  tiltMax_ = tx;
  // The unit's limits in head angles (a direction of -1 swaps min and max).
  auto range = [](long lo, long hi, double res, int dir) {
    const double a = dir * lo * res, b = dir * hi * res;
    return std::pair{std::min(a, b), std::max(a, b)};
  };
  const auto [panLo, panHi] = range(pn, px, panRes_, options_.panDirection);
  const auto [tiltLo, tiltHi] = range(tn, tx, tiltRes_, options_.tiltDirection);
  limits_ = options_.limits;
  limits_.panMin = std::max(limits_.panMin, panLo);
  limits_.panMax = std::min(limits_.panMax, panHi);
  limits_.tiltMin = std::max(limits_.tiltMin, tiltLo);
  limits_.tiltMax = std::min(limits_.tiltMax, tiltHi);
  limits_.hasVergence = false;
  limits_.vergenceMin = limits_.vergenceMax = 0;
  if (limits_.panMin > limits_.panMax || limits_.tiltMin > limits_.tiltMax)
    throw Error("the requested head limits do not overlap the PTU's own limits");
  worker_.start(options_.period, [this] { runGuardedCycle([this] { cycle(); }, mutex_, health_); });
}

PtuHead::~PtuHead() {
  shutdown();
}

ptu::Reply PtuHead::require(const std::string& command) {
  const auto r = exchange(command);
  if (!r)
    throw Error("the PTU on " + transport_->describe() + " does not answer '" + trimmed(command) +
                "': check the port, the baud rate (9600 by default) and the power (" +
                health().lastFault + ")");
  if (r->kind != ptu::ReplyKind::kOk)
    throw Error("the PTU refused '" + trimmed(command) + "': " + r->text);
  return *r;
}

// One command, one reply line; a query's value must pass `check` (if any).
// A malformed or implausible reply is counted and the command sent again.
// nullopt after the retries (reason in health()).
std::optional<ptu::Reply> PtuHead::exchange(const std::string& command, const ReplyCheck& check) {
  const std::string echo = trimmed(command);
  for (int attempt = 0; attempt <= options_.retries; ++attempt) {
    transport_->discardInput();
    rx_.clear();
    transport_->write(
        std::span(reinterpret_cast<const std::uint8_t*>(command.data()), command.size()));
    const auto deadline = Clock::now() + options_.replyTimeout;
    std::optional<ptu::Reply> reply;
    std::string problem;
    while (!reply && problem.empty()) {
      if (auto line = ptu::takeLine(rx_)) {
        std::string l = *line;
        if (l.rfind(echo, 0) == 0) l = l.substr(echo.size());  // an echo before ED took effect
        try {
          const ptu::Reply r = ptu::parseReply(l);
          if (r.kind == ptu::ReplyKind::kLimitHit) {
            std::lock_guard lock(mutex_);
            health_.lastFault = std::string(r.text == "P" ? "pan" : "tilt") + " axis hit its limit";
            continue;
          }
          if (check && r.kind == ptu::ReplyKind::kOk) problem = check(r);
          reply = r;
        } catch (const Error& e) {
          problem = e.what();
        }
        continue;
      }
      const auto now = Clock::now();
      if (now >= deadline) break;
      const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - now);
      const auto more = transport_->read(256, left);
      rx_.append(more.begin(), more.end());
    }
    std::lock_guard lock(mutex_);
    if (!problem.empty()) {
      ++health_.corruptReplies;
      health_.lastFault = problem;
      continue;
    }
    if (!reply) {
      ++health_.timeouts;
      health_.lastFault = "no reply to '" + echo + "' within " +
                          std::to_string(options_.replyTimeout.count()) + " ms";
      continue;
    }
    if (reply->kind == ptu::ReplyKind::kError) {
      ++health_.deviceErrors;
      health_.lastFault = "PTU: " + reply->text;
    } else {
      ++health_.exchanges;
    }
    return reply;
  }
  return std::nullopt;
}

void PtuHead::command(const HeadAngles& target, double speedRadPerS) {
  if (!std::isfinite(target.pan) || !std::isfinite(target.tilt) || !std::isfinite(speedRadPerS) ||
      speedRadPerS < 0)
    throw Error("head command must be finite angles and a speed >= 0");
  std::lock_guard lock(mutex_);
  target_.pan = std::clamp(target.pan, limits_.panMin, limits_.panMax);
  target_.tilt = std::clamp(target.tilt, limits_.tiltMin, limits_.tiltMax);
  target_.vergence = 0;
  speed_ = std::min(speedRadPerS > 0 ? speedRadPerS : options_.defaultSpeed, limits_.maxSpeed);
  haltRequested_ = false;
  ++targetGeneration_;
}

std::optional<HeadMeasurement> PtuHead::measured() const {
  std::lock_guard lock(mutex_);
  return measured_;
}

void PtuHead::halt() {
  std::lock_guard lock(mutex_);
  haltRequested_ = true;
}

HeadHealth PtuHead::health() const {
  std::lock_guard lock(mutex_);
  return health_;
}

void PtuHead::cycle() {
  HeadAngles target;
  double speed;
  long generation;
  bool haltNow;
  {
    std::lock_guard lock(mutex_);
    target = target_;
    speed = speed_;
    generation = targetGeneration_;
    haltNow = haltRequested_;
    haltRequested_ = false;
  }
  if (haltNow) {
    exchange(ptu::halt());
    sentGeneration_ = generation;
  } else if (generation != sentGeneration_) {
    const long panSpeed = std::max(1L, std::lround(speed / panRes_));
    const long tiltSpeed = std::max(1L, std::lround(speed / tiltRes_));
    auto accepted = [this](const std::string& c) {
      const auto r = exchange(c);
      return r && r->kind == ptu::ReplyKind::kOk;
    };
    const bool ok =
        accepted(ptu::setSpeed(ptu::Axis::kPan, panSpeed)) &&
        accepted(ptu::setSpeed(ptu::Axis::kTilt, tiltSpeed)) &&
        accepted(ptu::setPosition(ptu::Axis::kPan,
                                  std::lround(options_.panDirection * target.pan / panRes_))) &&
        accepted(ptu::setPosition(ptu::Axis::kTilt,
                                  std::lround(options_.tiltDirection * target.tilt / tiltRes_)));
    if (ok) sentGeneration_ = generation;  // otherwise resend next cycle
  }
  auto position = [this](ptu::Axis axis) {
    return exchange(ptu::queryPosition(axis),
                    [this, axis](const ptu::Reply& r) { return positionProblem(r, axis); });
  };
  const auto pan = position(ptu::Axis::kPan);
  const auto tilt = pan ? position(ptu::Axis::kTilt) : std::nullopt;
  std::lock_guard lock(mutex_);
  if (!pan || !tilt || pan->kind != ptu::ReplyKind::kOk || tilt->kind != ptu::ReplyKind::kOk) {
    if (++failuresInARow_ >= options_.linkLostAfter) health_.linkUp = false;
    return;
  }
  HeadAngles a;  // both replies passed positionProblem()
  a.pan = options_.panDirection * ptu::parseInteger(*pan) * panRes_;
  a.tilt = options_.tiltDirection * ptu::parseInteger(*tilt) * tiltRes_;
  measured_ = HeadMeasurement{Clock::now(), a};
  failuresInARow_ = 0;
  health_.linkUp = true;
}

// A position reply must be an integer within the unit's limits, widened by a
// tenth of the range (a unit may stop a little past a soft limit).
std::string PtuHead::positionProblem(const ptu::Reply& reply, ptu::Axis axis) const {
  long v = 0;
  try {
    v = ptu::parseInteger(reply);
  } catch (const Error& e) {
    return e.what();
  }
  const bool pan = axis == ptu::Axis::kPan;
  const long lo = pan ? panMin_ : tiltMin_, hi = pan ? panMax_ : tiltMax_;
  const long margin = (hi - lo) / 10;
  if (v >= lo - margin && v <= hi + margin) return {};
  return std::string(pan ? "pan" : "tilt") + " position " + std::to_string(v) +
         " is outside the unit's range " + std::to_string(lo) + ".." + std::to_string(hi);
}

void PtuHead::shutdown() {
  if (!worker_.stop()) return;
  try {
    const std::string h = ptu::halt();
    transport_->write(std::span(reinterpret_cast<const std::uint8_t*>(h.data()), h.size()));
  } catch (const LinkError&) {
  }
}

}  // namespace horopter::hw
