// A pan-tilt(-vergence) head of DYNAMIXEL Protocol 2.0 servos on one bus.
//
// At start: pings every servo (an absent one is an error naming its ID),
// reads the pan and tilt servos' Velocity Limit and Min/Max Position Limit
// (the head's limits become the intersection of the options' and the
// servos'), enables torque, reads the present positions. Then its own thread, every
// period: when the target changed, a Sync Write of Profile Velocity (if the
// speed changed) and of Goal Position; always a Sync Read of Present
// Position, whose replies become the time-stamped measurement. Each exchange
// is retried (`retries`) on a timeout or a malformed reply (bad CRC, no ERROR
// byte, the wrong number of data bytes, ticks outside the Position Control
// Mode range): each counted in health(), never thrown, never an angle;
// `linkLostAfter` failed cycles in a row mark the link down. IDs must differ.
// The latest command wins; command() and measured() never wait for the bus.
//
// Vergence (a head with left and right eye servos): the total angle v is
// split equally, left eye +v/2, right eye -v/2 (both turn inward for v > 0,
// with "pan positive turns right" for each eye).
#pragma once

#include "horopter/core/export.hpp"

#include <functional>
#include <memory>
#include <mutex>
#include <optional>

#include "horopter/hardware/dynamixel_protocol.hpp"
#include "horopter/hardware/head.hpp"
#include "horopter/hardware/head_health.hpp"
#include "horopter/hardware/periodic_worker.hpp"
#include "horopter/hardware/transport.hpp"

namespace horopter::hw {

struct HOROPTER_API DynamixelHeadOptions {
  std::uint8_t panId = 1;
  std::uint8_t tiltId = 2;
  std::optional<std::uint8_t> leftVergenceId, rightVergenceId;  // both or neither
  dxl::ServoModel model;
  HeadLimits limits;          // hasVergence is set from the IDs
  double defaultSpeed = 0.5;  // rad/s when command() gets 0
  int panDirection = 1;       // +1 or -1: servo angle = direction * head angle
  int tiltDirection = 1;
  std::chrono::milliseconds period{20};
  std::chrono::milliseconds replyTimeout{50};
  int retries = 2;
  int linkLostAfter = 5;
};

class HOROPTER_API DynamixelHead final : public Head {
 public:
  // Throws horopter::Error if a servo does not answer its ping or options are bad.
  DynamixelHead(std::unique_ptr<ByteTransport> transport, DynamixelHeadOptions options = {});
  ~DynamixelHead() override;
  DynamixelHead(const DynamixelHead&) = delete;
  DynamixelHead& operator=(const DynamixelHead&) = delete;

  std::string name() const override;
  HeadLimits limits() const override { return options_.limits; }
  void command(const HeadAngles& target, double speedRadPerS = 0) override;
  std::optional<HeadMeasurement> measured() const override;
  void halt() override;

  HeadHealth health() const;
  // The model numbers the servos reported at start, in ID order (pan, tilt, left, right).
  std::vector<int> modelNumbers() const { return modelNumbers_; }
  void shutdown();

 private:
  // Why a reply's data is implausible, or "" when it is fine.
  using StatusCheck = std::function<std::string(const dxl::Status&)>;

  void readServoLimits();
  void cycle();
  std::vector<dxl::Status> exchange(const std::vector<std::uint8_t>& request,
                                    const std::vector<std::uint8_t>& ids, std::size_t dataLength,
                                    const StatusCheck& check = {});
  // Present Position of every servo in ID order, each checked; empty on failure.
  std::vector<std::int32_t> readPresentTicks();
  void fail(const std::string& what);
  std::vector<std::pair<std::uint8_t, std::int32_t>> goalTicks(const HeadAngles& a) const;
  HeadAngles anglesFromTicks(const std::vector<std::int32_t>& ticks) const;

  std::unique_ptr<ByteTransport> transport_;
  DynamixelHeadOptions options_;
  std::vector<std::uint8_t> ids_;
  std::vector<int> modelNumbers_;
  std::vector<std::uint8_t> rx_;
  long sentGeneration_ = 0;  // thread-only; nothing is sent before the first command()

  mutable std::mutex mutex_;
  HeadAngles target_;
  double speed_ = 0;
  long targetGeneration_ = 0;
  bool haltRequested_ = false;
  std::optional<HeadMeasurement> measured_;
  std::vector<std::int32_t> lastTicks_;
  HeadHealth health_;
  int failuresInARow_ = 0;

  PeriodicWorker worker_;  // last: stops before the members its cycles use
};

}  // namespace horopter::hw
