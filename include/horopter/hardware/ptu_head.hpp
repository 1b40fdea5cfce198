// A FLIR / Directed Perception pan-tilt unit through its ASCII command set
// (ptu_protocol.hpp). No vergence: HeadLimits::hasVergence is false and
// vergence commands are ignored.
//
// At start: FT (terse), ED (no echo; the echo of these first commands is
// stripped), CI (independent position control), then PR/TR resolutions and
// PN/PX/TN/TX limits (the head's limits become the intersection of the
// options' and the unit's). Then its own thread, every period: on a new
// target PS/TS speeds and PP/TP positions, on halt() H; always PP and TP
// queries, which become the time-stamped measurement. Replies that time out,
// do not parse, or report a position outside the unit's own limits (by more
// than a tenth of the range) are retried and counted, never an angle;
// "!P"/"!T" limit hits are reported.
#pragma once

#include "horopter/core/export.hpp"

#include <functional>
#include <memory>
#include <mutex>
#include <optional>

#include "horopter/hardware/head.hpp"
#include "horopter/hardware/head_health.hpp"
#include "horopter/hardware/periodic_worker.hpp"
#include "horopter/hardware/ptu_protocol.hpp"
#include "horopter/hardware/transport.hpp"

namespace horopter::hw {

struct HOROPTER_API PtuHeadOptions {
  HeadLimits limits;
  double defaultSpeed = 0.5;  // rad/s when command() gets 0
  // Head angle = direction * PTU angle. Our tilt is positive looking down; the
  // FLIR units' positive tilt raises the payload, hence -1 (check on yours).
  int panDirection = 1;
  int tiltDirection = -1;
  std::chrono::milliseconds period{20};
  std::chrono::milliseconds replyTimeout{200};
  int retries = 1;
  int linkLostAfter = 5;
};

class HOROPTER_API PtuHead final : public Head {
 public:
  // Throws horopter::Error when the unit does not answer the set-up queries.
  PtuHead(std::unique_ptr<ByteTransport> transport, PtuHeadOptions options = {});
  ~PtuHead() override;
  PtuHead(const PtuHead&) = delete;
  PtuHead& operator=(const PtuHead&) = delete;

  std::string name() const override { return "FLIR PTU on " + transport_->describe(); }
  HeadLimits limits() const override { return limits_; }
  void command(const HeadAngles& target, double speedRadPerS = 0) override;
  std::optional<HeadMeasurement> measured() const override;
  void halt() override;

  HeadHealth health() const;
  double panResolutionRad() const { return panRes_; }
  double tiltResolutionRad() const { return tiltRes_; }
  void shutdown();

 private:
  // Why an answer's value is implausible, or "" when it is fine.
  using ReplyCheck = std::function<std::string(const ptu::Reply&)>;

  std::optional<ptu::Reply> exchange(const std::string& command, const ReplyCheck& check = {});
  ptu::Reply require(const std::string& command);  // throws horopter::Error (set-up only)
  std::string positionProblem(const ptu::Reply& reply, ptu::Axis axis) const;
  void cycle();

  std::unique_ptr<ByteTransport> transport_;
  PtuHeadOptions options_;
  HeadLimits limits_;
  double panRes_ = 0, tiltRes_ = 0;                           // rad per position
  long panMin_ = 0, panMax_ = 0, tiltMin_ = 0, tiltMax_ = 0;  // the unit's limits, positions
  std::string rx_;
  long sentGeneration_ = 0;  // thread-only; nothing is sent before the first command()

  mutable std::mutex mutex_;
  HeadAngles target_;
  double speed_ = 0;
  long targetGeneration_ = 0;
  bool haltRequested_ = false;
  std::optional<HeadMeasurement> measured_;
  HeadHealth health_;
  int failuresInARow_ = 0;

  PeriodicWorker worker_;  // last: stops before the members its cycles use
};

}  // namespace horopter::hw
