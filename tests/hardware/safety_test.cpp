// The base's safety rules with a fake clock (time points we choose; nothing
// sleeps, nothing reads the wall clock): watchdog, velocity and acceleration
// limits, latching e-stop; then the same rules through the RMP driver on the
// in-process CAN bus with the simulated RMP, stepped by hand; last the
// watchdog in real time, both threads running, on the in-process bus and
// over the simulated RMP's pseudo-terminal.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <thread>

#include "horopter/core/error.hpp"
#include "horopter/hardware/can_transports.hpp"
#include "horopter/hardware/rmp_base.hpp"
#include "horopter/hardware/serial_port.hpp"
#include "horopter/hardware/sim_rmp.hpp"
#include "horopter/hardware/velocity_governor.hpp"

using namespace horopter::hw;
using namespace std::chrono_literals;

namespace {

BaseSafetyLimits fastLimits() {
  BaseSafetyLimits l;
  l.maxLinear = 1.0;
  l.maxAngular = 1.0;
  l.maxLinearAccel = 20.0;  // reach any target within one 50 ms step
  l.maxAngularAccel = 50.0;
  return l;
}

const Clock::time_point t0{std::chrono::seconds(1000)};

}  // namespace

TEST(Watchdog, FreshCommandPassesStaleCommandStops) {
  VelocityGovernor g(fastLimits());
  g.output(t0);
  g.command({0.4, 0.1}, t0);
  EXPECT_DOUBLE_EQ(g.output(t0 + 50ms).linear, 0.4);
  EXPECT_DOUBLE_EQ(g.output(t0 + 200ms).linear, 0.4);  // exactly 200 ms: still fresh
  EXPECT_FALSE(g.watchdogTripped());
  const BaseVelocity late = g.output(t0 + 201ms);
  EXPECT_EQ(late.linear, 0.0);
  EXPECT_EQ(late.angular, 0.0);
  EXPECT_TRUE(g.watchdogTripped());
  EXPECT_EQ(g.watchdogTrips(), 1);
  g.output(t0 + 400ms);
  EXPECT_EQ(g.watchdogTrips(), 1);  // one trip, counted once
  g.command({0.2, 0}, t0 + 450ms);
  EXPECT_DOUBLE_EQ(g.output(t0 + 500ms).linear, 0.2);
  EXPECT_FALSE(g.watchdogTripped());
}

TEST(Watchdog, NoCommandEverMeansZero) {
  VelocityGovernor g(fastLimits());
  EXPECT_EQ(g.output(t0).linear, 0.0);
  EXPECT_EQ(g.output(t0 + 10s).linear, 0.0);
  EXPECT_EQ(g.watchdogTrips(), 0);
}

TEST(Limits, VelocityIsClamped) {
  VelocityGovernor g(fastLimits());
  g.output(t0);
  g.command({5.0, -7.0}, t0);
  const BaseVelocity v = g.output(t0 + 100ms);
  EXPECT_DOUBLE_EQ(v.linear, 1.0);
  EXPECT_DOUBLE_EQ(v.angular, -1.0);
}

TEST(Limits, AccelerationIsRateLimited) {
  BaseSafetyLimits l = fastLimits();
  l.maxLinearAccel = 0.5;   // m/s^2
  l.maxAngularAccel = 1.0;  // rad/s^2
  VelocityGovernor g(l);
  g.output(t0);
  g.command({1.0, 1.0}, t0);
  BaseVelocity v = g.output(t0 + 100ms);
  EXPECT_NEAR(v.linear, 0.05, 1e-12);
  EXPECT_NEAR(v.angular, 0.1, 1e-12);
  g.command({1.0, 1.0}, t0 + 150ms);
  v = g.output(t0 + 200ms);
  EXPECT_NEAR(v.linear, 0.10, 1e-12);
  // Reversal also ramps (no instant jump from +0.1 to -1).
  g.command({-1.0, 0}, t0 + 250ms);
  v = g.output(t0 + 300ms);
  EXPECT_NEAR(v.linear, 0.05, 1e-12);
}

TEST(EmergencyStop, LatchesAndDropsCommandsUntilReleased) {
  VelocityGovernor g(fastLimits());
  g.output(t0);
  g.command({0.5, 0}, t0);
  EXPECT_GT(g.output(t0 + 20ms).linear, 0.0);
  g.emergencyStop();
  EXPECT_EQ(g.output(t0 + 40ms).linear, 0.0);
  g.command({0.5, 0}, t0 + 60ms);  // ignored while latched
  EXPECT_EQ(g.output(t0 + 80ms).linear, 0.0);
  EXPECT_TRUE(g.emergencyStopped());
  g.releaseEmergencyStop();
  // Release alone does not resume the old command: a fresh one is needed.
  EXPECT_EQ(g.output(t0 + 100ms).linear, 0.0);
  g.command({0.3, 0}, t0 + 120ms);
  EXPECT_DOUBLE_EQ(g.output(t0 + 140ms).linear, 0.3);
}

TEST(Limits, BadInputIsAnError) {
  BaseSafetyLimits l;
  l.maxLinear = -1;
  EXPECT_THROW(VelocityGovernor{l}, horopter::Error);
  l = BaseSafetyLimits{};
  l.commandTimeout = 0ms;
  EXPECT_THROW(validate(l), horopter::Error);
  VelocityGovernor g(BaseSafetyLimits{});
  EXPECT_THROW(g.command(BaseVelocity{std::nan(""), 0}, t0), horopter::Error);
}

namespace {

// Driver and simulated RMP on one in-process bus, both stepped with fake time.
struct SteppedRig {
  Clock::time_point now = t0;
  InProcessCanBus bus;
  SimRmp sim;
  RmpBase base;

  explicit SteppedRig(BaseSafetyLimits limits)
      : sim(bus.deviceSide(), simOptions()), base(bus.takeHostSide(), baseOptions(limits, &now)) {}
  static SimRmpOptions simOptions() {
    SimRmpOptions o;
    o.startThread = false;
    return o;
  }
  static RmpBaseOptions baseOptions(BaseSafetyLimits limits, const Clock::time_point* now) {
    RmpBaseOptions o;
    o.clock = [now] { return *now; };
    o.limits = limits;
    o.startThread = false;
    return o;
  }
  // One 10 ms tick: the RMP reports, the driver reads and commands.
  void tick() {
    now += 10ms;
    sim.step(now);
    base.step(now);
  }
  void run(std::chrono::milliseconds d, std::optional<BaseVelocity> keepCommanding = {}) {
    for (auto t = 0ms; t < d; t += 10ms) {
      if (keepCommanding) base.command(*keepCommanding);
      tick();
    }
  }
};

}  // namespace

TEST(RmpDriverSafety, OdometryFollowsCommandsThroughTheRealFrames) {
  SteppedRig rig(fastLimits());
  rig.run(100ms);
  ASSERT_TRUE(rig.base.odometry().has_value());
  rig.run(2000ms, BaseVelocity{0.2, 0.0});
  auto odo = rig.base.odometry();
  ASSERT_TRUE(odo);
  // 2 s at 0.2 m/s (the command reaches the sim one tick after it is sent).
  EXPECT_NEAR(odo->x, 0.4, 0.01);
  EXPECT_NEAR(odo->y, 0.0, 1e-3);
  EXPECT_NEAR(odo->velocity.linear, 0.2, 1.0 / 332);
  EXPECT_NEAR(rig.sim.truth().x, odo->x, 0.005);
  // Turn in place: +0.5 rad/s for 1 s -> heading +0.5 rad (counter-clockwise).
  rig.run(1000ms, BaseVelocity{0.0, 0.5});
  odo = rig.base.odometry();
  EXPECT_NEAR(odo->heading, 0.5, 0.02);
  EXPECT_NEAR(rig.sim.truth().heading, odo->heading, 0.01);
  EXPECT_TRUE(rig.base.health().statusFresh);
  EXPECT_EQ(rig.sim.truth().resets, 4);  // the four reset-integrator commands at start
}

// The bound as stated: frames sent while the last command is at most 200 ms
// old carry it; the first frame after that carries zero, and the simulated
// RMP stands still from its next cycle (10 ms ticks here).
TEST(RmpDriverSafety, WatchdogStopsTheBaseWithin200msOfTheLastCommand) {
  SteppedRig rig(fastLimits());
  rig.run(500ms, BaseVelocity{0.3, 0.0});
  rig.base.command({0.3, 0.0});
  const Clock::time_point last = rig.now;
  while (rig.now < last + 200ms) {
    rig.tick();
    EXPECT_NEAR(rig.base.health().lastSent.linear, 0.3, 1e-9)
        << "stopped early, " << (rig.now - last) / 1ms << " ms after the last command";
  }
  EXPECT_EQ(rig.base.health().watchdogTrips, 0);
  rig.tick();  // the first step later than 200 ms
  EXPECT_EQ(rig.base.health().lastSent.linear, 0.0);
  EXPECT_EQ(rig.base.health().watchdogTrips, 1);
  rig.tick();  // the RMP reads that frame on its next cycle
  EXPECT_EQ(rig.sim.truth().velocity.linear, 0.0);
  EXPECT_EQ(rig.now - last, 220ms);
}

TEST(RmpDriverSafety, StatusTimeoutIsReportedAndStopsTheBase) {
  SteppedRig rig(fastLimits());
  rig.run(300ms, BaseVelocity{0.3, 0.0});
  EXPECT_TRUE(rig.base.health().statusFresh);
  rig.sim.injectFault(SimRmpFault::kSilent, 60);  // 600 ms without reports
  rig.run(600ms, BaseVelocity{0.3, 0.0});
  BaseHealth h = rig.base.health();
  EXPECT_FALSE(h.statusFresh);
  EXPECT_EQ(h.statusTimeouts, 1);
  EXPECT_NE(h.lastFault.find("no status"), std::string::npos);
  EXPECT_EQ(h.lastSent.linear, 0.0);
  // Reports resume: the base moves again (ramping from zero).
  rig.run(300ms, BaseVelocity{0.3, 0.0});
  h = rig.base.health();
  EXPECT_TRUE(h.statusFresh);
  EXPECT_GT(h.lastSent.linear, 0.0);
}

TEST(RmpDriverSafety, CorruptAndIncompleteSeriesAreCounted) {
  SteppedRig rig(fastLimits());
  rig.run(100ms);
  rig.sim.injectFault(SimRmpFault::kBadLength, 2);
  rig.run(30ms);
  EXPECT_GE(rig.base.health().badFrames, 2);
  const long before = rig.base.health().badFrames;
  rig.sim.injectFault(SimRmpFault::kMissingFrame, 1);
  rig.run(30ms);
  EXPECT_GT(rig.base.health().badFrames, before);
  EXPECT_NE(rig.base.health().lastFault.find("incomplete"), std::string::npos);
}

TEST(RmpDriverSafety, LostLinkIsReported) {
  SteppedRig rig(fastLimits());
  rig.run(100ms, BaseVelocity{0.2, 0.0});
  rig.bus.disconnect();
  rig.run(30ms, BaseVelocity{0.2, 0.0});
  const BaseHealth h = rig.base.health();
  EXPECT_FALSE(h.linkUp);
  EXPECT_NE(h.lastFault.find("disconnected"), std::string::npos);
}

TEST(RmpDriverSafety, EmergencyStopThroughTheDriver) {
  SteppedRig rig(fastLimits());
  rig.run(300ms, BaseVelocity{0.3, 0.0});
  rig.base.emergencyStop();
  rig.run(100ms, BaseVelocity{0.3, 0.0});
  EXPECT_TRUE(rig.base.emergencyStopped());
  EXPECT_EQ(rig.base.health().lastSent.linear, 0.0);
  EXPECT_NEAR(rig.sim.truth().velocity.linear, 0.0, 1e-9);
  rig.base.releaseEmergencyStop();
  rig.run(100ms, BaseVelocity{0.3, 0.0});
  EXPECT_GT(rig.sim.truth().velocity.linear, 0.0);
}

TEST(RmpDriverSafety, ShutdownSendsZeroVelocity) {
  SteppedRig rig(fastLimits());
  rig.run(300ms, BaseVelocity{0.3, 0.0});
  EXPECT_GT(rig.sim.truth().velocity.linear, 0.0);
  rig.base.shutdown();
  rig.now += 10ms;
  rig.sim.step(rig.now);
  EXPECT_EQ(rig.sim.truth().velocity.linear, 0.0);
}

TEST(RmpDriverSafety, TheRmpsOwnEmergencyStopIsReported) {
  SteppedRig rig(fastLimits());
  rig.run(100ms, BaseVelocity{0.2, 0.0});
  EXPECT_EQ(rig.base.health().motorsEnabled, true);
  rig.sim.pressEmergencyStop(true);
  rig.run(50ms, BaseVelocity{0.2, 0.0});
  const BaseHealth h = rig.base.health();
  EXPECT_EQ(h.motorsEnabled, false);
  EXPECT_NE(h.lastFault.find("e-stop is pressed"), std::string::npos);
  EXPECT_EQ(rig.base.odometry()->velocity.linear, 0.0);
}

// What `horopter base --help` says about stopping: zero commanded at the
// default 0.5 m/s^2 ramps down from 0.4 m/s in 0.8 s over 0.16 m.
TEST(RmpDriverSafety, AZeroCommandRampsDownAtTheAccelerationLimit) {
  SteppedRig rig(BaseSafetyLimits{});
  rig.run(1500ms, BaseVelocity{0.4, 0.0});
  ASSERT_NEAR(rig.sim.truth().velocity.linear, 0.4, 1.0 / 332);
  const double x0 = rig.sim.truth().x;
  const Clock::time_point t0 = rig.now;
  while (rig.sim.truth().velocity.linear > 0 && rig.now < t0 + 3s)
    rig.run(10ms, BaseVelocity{0.0, 0.0});
  EXPECT_NEAR(std::chrono::duration<double>(rig.now - t0).count(), 0.8, 0.03);
  EXPECT_NEAR(rig.sim.truth().x - x0, 0.16, 0.01);
}

// Real time, both threads running (driver at 50 Hz, RMP at 100 Hz): the base
// stands still 200 ms after the last command, plus at most one driver period,
// one RMP cycle and some scheduling slack for a loaded machine.
namespace {

void expectWatchdogStopsInRealTime(RmpBase& base, SimRmp& sim) {
  const auto until = Clock::now() + 600ms;
  while (Clock::now() < until) {
    base.command({0.3, 0.0});
    std::this_thread::sleep_for(20ms);
  }
  ASSERT_NEAR(sim.truth().velocity.linear, 0.3, 1.0 / 332);
  base.command({0.3, 0.0});
  const Clock::time_point last = Clock::now();
  Clock::time_point stopped = last;
  while (sim.truth().velocity.linear != 0.0 && Clock::now() < last + 2s) {
    std::this_thread::sleep_for(1ms);
    stopped = Clock::now();
  }
  const auto ms = std::chrono::duration<double, std::milli>(stopped - last).count();
  std::printf("base stood still %.1f ms after the last command (%s)\n", ms, base.name().c_str());
  EXPECT_GE(ms, 200.0 - 1.0);  // never earlier than the watchdog allows
  EXPECT_LE(ms, 200.0 + 20 + 10 + 40);
  EXPECT_EQ(base.health().watchdogTrips, 1);
}

}  // namespace

TEST(RmpDriverSafetyRealTime, WatchdogStopsTheBaseAbout200msAfterTheLastCommand) {
  InProcessCanBus bus;
  SimRmp sim(bus.deviceSide());
  RmpBaseOptions o;
  o.limits = fastLimits();
  RmpBase base(bus.takeHostSide(), o);
  expectWatchdogStopsInRealTime(base, sim);
}

// The same through a real tty: the driver opens the simulated RMP's
// pseudo-terminal as it opens /dev/ttyUSB1 (SerialPort, the USB framing).
TEST(RmpDriverSafetyRealTime, WatchdogStopsTheBaseOverItsPseudoTerminal) {
  SimRmpOnPty sim;
  RmpBaseOptions o;
  o.limits = fastLimits();
  RmpBase base(std::make_unique<RmpUsbCan>(std::make_unique<SerialPort>(sim.port())), o);
  expectWatchdogStopsInRealTime(base, sim.rmp());
  EXPECT_GT(sim.rmp().truth().motionFrames, 30);
}
