// Devices that speak the protocol but say nonsense (issue 22): a DYNAMIXEL
// status packet with a valid CRC and no ERROR byte or short data, ticks no
// servo reports, a PTU answering "inf", an RMP reporting 99 m/s. Each is a
// counted fault in health() and retried; none throws out of a driver thread
// and none becomes a measured angle or a velocity.
#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "eventually.hpp"
#include "horopter/hardware/can_transports.hpp"
#include "horopter/hardware/dynamixel_head.hpp"
#include "horopter/hardware/ptu_head.hpp"
#include "horopter/hardware/rmp_base.hpp"
#include "horopter/hardware/serial_port.hpp"
#include "horopter/hardware/sim_devices.hpp"
#include "horopter/hardware/sim_rmp.hpp"

using namespace horopter::hw;
using namespace std::chrono_literals;

namespace {

using horopter::test::eventually;

// Every measurement within the head's limits while `condition` is awaited.
template <typename H, typename F>
bool eventuallyWithSaneAngles(const H& head, F condition) {
  const HeadLimits l = head.limits();
  return eventually([&] {
    if (auto m = head.measured()) {
      EXPECT_TRUE(m->angles.pan >= l.panMin - 0.01 && m->angles.pan <= l.panMax + 0.01)
          << "pan " << m->angles.pan;
      EXPECT_TRUE(m->angles.tilt >= l.tiltMin - 0.01 && m->angles.tilt <= l.tiltMax + 0.01)
          << "tilt " << m->angles.tilt;
    }
    return condition();
  });
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::unique_ptr<DynamixelHead> openHead(SimDynamixelBus& bus, DynamixelHeadOptions o = {}) {
  return std::make_unique<DynamixelHead>(std::make_unique<SerialPort>(bus.port()), o);
}

std::unique_ptr<PtuHead> openHead(SimPtu& sim, PtuHeadOptions o = {}) {
  return std::make_unique<PtuHead>(std::make_unique<SerialPort>(sim.port(), SerialOptions{9600}),
                                   o);
}

// One bad reply, sent by `inject`: counted as corrupt, retried, the head
// keeps measuring. The health before is read before the injection: the
// driver's thread may take the reply before this thread looks (it did under
// ThreadSanitizer), and then no later count would ever exceed it.
template <typename H, typename Inject>
void expectOneCountedFault(const H& head, Inject inject, const std::string& faultText) {
  const HeadHealth before = head.health();
  inject();
  ASSERT_TRUE(eventuallyWithSaneAngles(head, [&] {
    const HeadHealth h = head.health();
    return h.corruptReplies > before.corruptReplies && h.exchanges > before.exchanges + 2;
  })) << head.health().lastFault;
  EXPECT_TRUE(contains(head.health().lastFault, faultText)) << head.health().lastFault;
  EXPECT_TRUE(head.health().linkUp);
}

}  // namespace

TEST(DynamixelMalformedReply, StatusWithoutErrorByteIsAFaultNotACrash) {
  SimDynamixelBus bus({1, 2});
  auto head = openHead(bus);
  // A valid CRC, instruction 0x55, no parameters at all.
  const auto noErrorByte = [&] { bus.injectStatus({}, 1); };
  expectOneCountedFault(*head, noErrorByte, "no ERROR byte");
}

TEST(DynamixelMalformedReply, EmptyOrShortPresentPositionIsAFault) {
  SimDynamixelBus bus({1, 2});
  auto head = openHead(bus);
  const auto errorByteOnly = [&] { bus.injectStatus({0x00}, 1); };  // no position
  expectOneCountedFault(*head, errorByteOnly, "0 data bytes, expected 4");
  const auto twoOfFourBytes = [&] { bus.injectStatus({0x00, 0x34, 0x12}, 1); };
  expectOneCountedFault(*head, twoOfFourBytes, "2 data bytes, expected 4");
}

TEST(DynamixelMalformedReply, OutOfRangeTicksNeverBecomeAnAngle) {
  SimDynamixelBus bus({1, 2});
  DynamixelHeadOptions o;
  o.linkLostAfter = 3;
  auto head = openHead(bus, o);
  const auto twoTurns = [&] { bus.injectStatus({0x00, 0x00, 0x20, 0x00, 0x00}, 1); };  // 8192 ticks
  expectOneCountedFault(*head, twoTurns, "8192");
  // 0x7FFFFFFF ticks for good: never an angle (3 294 195 rad before), the link goes down.
  bus.injectStatus({0x00, 0xFF, 0xFF, 0xFF, 0x7F}, 1000000);
  ASSERT_TRUE(eventuallyWithSaneAngles(*head, [&] { return !head->health().linkUp; }));
  EXPECT_TRUE(contains(head->health().lastFault, "2147483647")) << head->health().lastFault;
  bus.injectStatus({}, 0);
  EXPECT_TRUE(eventuallyWithSaneAngles(*head, [&] { return head->health().linkUp; }));
}

TEST(PtuMalformedReply, NonFiniteOrHugeNumbersAreFaults) {
  SimPtu sim;
  auto head = openHead(sim);
  for (const char* reply : {"* inf", "* -inf", "* nan", "* infinity", "* 1e300",
                            "* 9223372036854775807", "* 12abc", "*"}) {
    SCOPED_TRACE(reply);
    const auto send = [&] { sim.injectReply(reply, 1); };
    expectOneCountedFault(*head, send, "");
  }
}

TEST(PtuMalformedReply, PositionOutsideTheUnitsRangeIsAFault) {
  SimPtu sim;  // pan -3090 .. 3090 positions
  PtuHeadOptions o;
  o.linkLostAfter = 3;
  auto head = openHead(sim, o);
  sim.injectReply("* 99999999", 1000000);
  ASSERT_TRUE(eventuallyWithSaneAngles(*head, [&] { return !head->health().linkUp; }));
  EXPECT_TRUE(contains(head->health().lastFault, "99999999")) << head->health().lastFault;
  sim.injectReply("", 0);
  EXPECT_TRUE(eventuallyWithSaneAngles(*head, [&] { return head->health().linkUp; }));
}

TEST(RmpMalformedFeedback, ImplausibleStatusValuesAreBadFramesNotOdometry) {
  InProcessCanBus bus;
  SimRmp sim(bus.deviceSide());
  RmpBase base(bus.takeHostSide());
  ASSERT_TRUE(eventually([&] { return base.odometry().has_value(); }));
  const long before = base.health().badFrames;
  sim.injectFault(SimRmpFault::kWildValues, 20);  // 0.2 s of 99 m/s wheels, mode 9
  ASSERT_TRUE(eventually([&] {
    const auto o = base.odometry();
    EXPECT_LT(std::abs(o->velocity.linear), 1.0) << "wheel speeds of 99 m/s were believed";
    EXPECT_LT(std::abs(o->x), 1.0);
    return base.health().badFrames >= before + 20;
  }));
  EXPECT_TRUE(base.health().linkUp);
}
