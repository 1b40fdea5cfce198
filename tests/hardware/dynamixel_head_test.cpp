// The real DYNAMIXEL head driver against the simulated bus over a real
// pseudo-terminal (SerialPort on the pty's slave), including injected faults.
// Waits poll for a condition with a generous limit; nothing asserts on time.
#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "eventually.hpp"
#include "horopter/core/error.hpp"
#include "horopter/hardware/dynamixel_head.hpp"
#include "horopter/hardware/serial_port.hpp"
#include "horopter/hardware/sim_devices.hpp"

using namespace horopter::hw;
using namespace std::chrono_literals;

namespace {

using horopter::test::eventually;

std::unique_ptr<DynamixelHead> openHead(SimDynamixelBus& bus, DynamixelHeadOptions o = {}) {
  return std::make_unique<DynamixelHead>(std::make_unique<SerialPort>(bus.port()), o);
}

}  // namespace

TEST(DynamixelHeadOnPty, PingsEnablesTorqueAndFollowsCommands) {
  SimDynamixelBus bus({1, 2});
  // This test counts timeouts, so the simulated bus gets a second to answer:
  // on a loaded machine its thread can miss the 50 ms default (a fresh-clone
  // run beside valgrind and a build saw one), which is scheduling, not a
  // protocol fault.
  DynamixelHeadOptions patient;
  patient.replyTimeout = 1000ms;
  auto head = openHead(bus, patient);
  EXPECT_EQ(head->modelNumbers(), (std::vector<int>{1020, 1020}));
  EXPECT_TRUE(bus.torqueOn(1));
  EXPECT_TRUE(bus.torqueOn(2));
  head->command({0.2, -0.1, 0}, 1.0);
  ASSERT_TRUE(eventually([&] {
    auto m = head->measured();
    return m && std::abs(m->angles.pan - 0.2) < 0.002 && std::abs(m->angles.tilt + 0.1) < 0.002;
  })) << head->health().lastFault;
  // The wire carried the goal in ticks: 0.2 rad -> 2048 + 130.
  EXPECT_EQ(bus.goalTicks(1), 2048 + 130);
  EXPECT_TRUE(head->health().linkUp);
  EXPECT_EQ(head->health().timeouts, 0);
}

TEST(DynamixelHeadOnPty, LimitsClampTheTarget) {
  SimDynamixelBus bus({1, 2});
  DynamixelHeadOptions o;
  o.limits.panMax = 0.3;
  auto head = openHead(bus, o);
  head->command({1.4, 0, 0});
  ASSERT_TRUE(eventually([&] { return bus.goalTicks(1) != 2048; }));
  EXPECT_EQ(bus.goalTicks(1), dxl::radiansToTicks(0.3, dxl::ServoModel{}));
  EXPECT_THROW(head->command({std::nan(""), 0, 0}), horopter::Error);
}

TEST(DynamixelHeadOnPty, ServoLimitsNarrowTheHeadsLimits) {
  SimDynamixelBus bus({1, 2});
  bus.setLimits(1, 1800, 2300, 100);  // pan: -0.380 .. +0.387 rad, 100 units = 2.40 rad/s
  auto head = openHead(bus);
  const dxl::ServoModel x;
  EXPECT_DOUBLE_EQ(head->limits().panMin, dxl::ticksToRadians(1800, x));
  EXPECT_DOUBLE_EQ(head->limits().panMax, dxl::ticksToRadians(2300, x));
  EXPECT_DOUBLE_EQ(head->limits().tiltMax, 0.8);   // the options' limit is the narrower one
  EXPECT_DOUBLE_EQ(head->limits().maxSpeed, 1.0);  // 167 and 100 units are faster than 1 rad/s
  head->command({1.0, 0, 0});
  ASSERT_TRUE(eventually([&] { return bus.goalTicks(1) != 2048; }));
  EXPECT_EQ(bus.goalTicks(1), 2300);
}

TEST(DynamixelHeadOnPty, VergenceServosSplitTheAngle) {
  SimDynamixelBus bus({1, 2, 3, 4});
  DynamixelHeadOptions o;
  o.leftVergenceId = 3;
  o.rightVergenceId = 4;
  o.limits.vergenceMax = 0.4;
  auto head = openHead(bus, o);
  EXPECT_TRUE(head->limits().hasVergence);
  head->command({0, 0, 0.2}, 1.0);
  ASSERT_TRUE(eventually([&] {
    auto m = head->measured();
    return m && std::abs(m->angles.vergence - 0.2) < 0.003;
  }));
  EXPECT_NEAR(bus.positionRad(3), 0.1, 0.002);
  EXPECT_NEAR(bus.positionRad(4), -0.1, 0.002);
}

TEST(DynamixelHeadOnPty, MissingServoIsAClearError) {
  SimDynamixelBus bus({1});
  try {
    openHead(bus);
    FAIL() << "a head without servo 2 must not open";
  } catch (const horopter::Error& e) {
    EXPECT_NE(std::string(e.what()).find("ID 2"), std::string::npos) << e.what();
  }
}

TEST(DynamixelHeadOnPty, CorruptShortAndGarbageRepliesAreRetriedAndCounted) {
  SimDynamixelBus bus({1, 2});
  auto head = openHead(bus);
  for (DeviceFault f :
       {DeviceFault::kCorruptChecksum, DeviceFault::kShortFrame, DeviceFault::kGarbage}) {
    const HeadHealth before = head->health();
    bus.injectFault(f, 1);
    ASSERT_TRUE(eventually([&] {
      const HeadHealth h = head->health();
      return h.corruptReplies + h.timeouts > before.corruptReplies + before.timeouts &&
             h.exchanges > before.exchanges + 2;
    })) << "fault "
        << static_cast<int>(f) << ": " << head->health().lastFault;
    EXPECT_TRUE(head->health().linkUp);  // one bad reply is retried, not a lost link
  }
  head->command({-0.3, 0.1, 0}, 2.0);
  EXPECT_TRUE(eventually([&] {
    auto m = head->measured();
    return m && std::abs(m->angles.pan + 0.3) < 0.002;
  }));
}

TEST(DynamixelHeadOnPty, NoReplyTimesOutAndLongSilenceMarksTheLinkDown) {
  SimDynamixelBus bus({1, 2});
  DynamixelHeadOptions o;
  o.replyTimeout = 10ms;
  o.retries = 0;
  o.linkLostAfter = 3;
  auto head = openHead(bus, o);
  bus.injectFault(DeviceFault::kNoReply, 1000000);
  ASSERT_TRUE(eventually([&] { return !head->health().linkUp; }));
  EXPECT_GE(head->health().timeouts, 3);
  EXPECT_NE(head->health().lastFault.find("no reply"), std::string::npos);
  bus.injectFault(DeviceFault::kNone, 0);
  EXPECT_TRUE(eventually([&] { return head->health().linkUp; }));
}

TEST(DynamixelHeadOnPty, DisconnectMidRunIsReported) {
  SimDynamixelBus bus({1, 2});
  auto head = openHead(bus);
  bus.injectFault(DeviceFault::kDisconnect, 1);
  ASSERT_TRUE(eventually([&] { return !head->health().linkUp; }));
  EXPECT_FALSE(head->health().lastFault.empty());
  head->shutdown();  // joins cleanly with the link gone
}

TEST(DynamixelHeadOnPty, DuplicateIdsAreAnError) {
  SimDynamixelBus bus({1, 2, 3});
  DynamixelHeadOptions o;
  o.tiltId = 1;  // pan and tilt on one servo
  EXPECT_THROW(openHead(bus, o), horopter::Error);
  o = {};
  o.leftVergenceId = 3;
  o.rightVergenceId = 2;  // the tilt servo again
  EXPECT_THROW(openHead(bus, o), horopter::Error);
}
