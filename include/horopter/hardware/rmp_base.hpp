// The Segway RMP driver: hw::Base over any CanTransport (SocketCAN, the RMP's
// USB framing, the in-process bus of the simulator).
//
// Its own thread runs a fixed-rate cycle (default 50 Hz): read every status
// frame that arrived, then send one 0x413 motion frame with the velocity the
// VelocityGovernor allows. command() only stores the latest request, so the
// vision pipeline never blocks on the bus. Faults are reported in health(),
// never swallowed: a watchdog trip, a status timeout (no complete status
// series within statusTimeout -> zero velocity until reports resume), a
// broken link, undecodable frames. Shutdown (destructor or shutdown()) sends
// zero velocity and joins the thread.
//
// For tests with a fake clock: options.startThread = false, then call
// step(now) with the time you choose.
#pragma once

#include "horopter/core/export.hpp"

#include <functional>
#include <memory>
#include <mutex>

#include "horopter/hardware/base.hpp"
#include "horopter/hardware/periodic_worker.hpp"
#include "horopter/hardware/rmp_protocol.hpp"
#include "horopter/hardware/transport.hpp"
#include "horopter/hardware/velocity_governor.hpp"

namespace horopter::hw {

struct HOROPTER_API RmpBaseOptions {
  rmp::Scaling scaling = rmp::scalingRmp200();
  BaseSafetyLimits limits;
  std::chrono::milliseconds period{20};  // motion frame rate; 5 .. 200 ms
  bool resetIntegratorsAtStart = true;   // as libsegwayrmp's connect() does
  bool startThread = true;
  // Time source for command stamps and the thread's cycles; tests inject a fake.
  std::function<Clock::time_point()> clock = [] { return Clock::now(); };
};

struct HOROPTER_API BaseHealth {
  bool linkUp = true;        // false after a LinkError from the transport
  bool statusFresh = false;  // a complete status series within statusTimeout
  bool watchdogTripped = false;
  long watchdogTrips = 0;
  long statusTimeouts = 0;  // transitions fresh -> stale (or none at start)
  long badFrames = 0;       // status frames with a wrong length or implausible values
  long framesSent = 0;
  long seriesReceived = 0;
  // The RMP's own motor status (0x680): false while its e-stop button is pressed.
  std::optional<bool> motorsEnabled;
  std::string lastFault;  // empty when nothing went wrong yet
  BaseVelocity lastSent;  // what the last motion frame asked for
};

class HOROPTER_API RmpBase final : public Base {
 public:
  // Throws horopter::Error for bad options.
  RmpBase(std::unique_ptr<CanTransport> transport, RmpBaseOptions options = {});
  ~RmpBase() override;
  RmpBase(const RmpBase&) = delete;
  RmpBase& operator=(const RmpBase&) = delete;

  std::string name() const override;
  void command(const BaseVelocity& velocity) override;
  void emergencyStop() override;
  void releaseEmergencyStop() override;
  bool emergencyStopped() const override;
  std::optional<Odometry> odometry() const override;

  BaseHealth health() const;
  std::optional<rmp::Status> lastStatus() const;
  // One control cycle at `now` (the thread calls it; tests call it themselves).
  void step(Clock::time_point now);
  // Zero velocity (best effort), thread joined. Idempotent.
  void shutdown();

 private:
  void receiveAll(Clock::time_point now);
  void completeSeries(Clock::time_point now);
  void send(const CanFrame& frame);

  std::unique_ptr<CanTransport> transport_;
  RmpBaseOptions options_;
  mutable std::mutex mutex_;  // everything below
  VelocityGovernor governor_;
  rmp::Status partial_;
  bool partialHasBadFrame_ = false;  // a frame of this series was rejected
  std::optional<rmp::Status> status_;
  std::optional<Odometry> odometry_;
  double lastForeAft_ = 0, lastYaw_ = 0;
  Clock::time_point start_{}, lastSeries_{};
  bool started_ = false;
  bool staleReported_ = false;
  BaseHealth health_;
  std::mutex stepMutex_;   // one step at a time (thread vs shutdown)
  PeriodicWorker worker_;  // last: stops before the members its cycles use
};

}  // namespace horopter::hw
