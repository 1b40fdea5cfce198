// The real PTU driver against the simulated PTU over a real pseudo-terminal
// (the simulator starts with echo on and verbose feedback, as a unit out of
// the box), plus a byte-exact scripted exchange and injected faults.
#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "eventually.hpp"
#include "horopter/core/error.hpp"
#include "horopter/hardware/ptu_head.hpp"
#include "horopter/hardware/scripted_transport.hpp"
#include "horopter/hardware/serial_port.hpp"
#include "horopter/hardware/sim_devices.hpp"

using namespace horopter::hw;
using namespace std::chrono_literals;

namespace {

using horopter::test::eventually;

std::unique_ptr<PtuHead> openHead(SimPtu& sim, PtuHeadOptions o = {}) {
  return std::make_unique<PtuHead>(std::make_unique<SerialPort>(sim.port(), SerialOptions{9600}),
                                   o);
}

}  // namespace

// The set-up sequence byte for byte, echo included, against a script.
TEST(PtuHeadScripted, SetUpSequenceIsExact) {
  auto script = std::make_unique<ScriptedTransport>();
  ScriptedTransport& s = *script;
  s.expect("FT ", "FT *\r\n");  // still echoing
  s.expect("ED ", "ED *\r\n");
  s.expect("CI ", "*\r\n");
  s.expect("PR ", "* 185.1428\r\n");
  s.expect("TR ", "* 46.2857\r\n");
  s.expect("PN ", "* -3090\r\n");
  s.expect("PX ", "* 3090\r\n");
  s.expect("TN ", "* -907\r\n");
  s.expect("TX ", "* 604\r\n");
  // The first cycle: position queries (then the script runs out: silence).
  s.expect("PP ", "* 100\r\n");
  s.expect("TP ", "* -50\r\n");
  PtuHeadOptions o;
  o.replyTimeout = 1ms;
  PtuHead head(std::move(script), o);
  EXPECT_NEAR(head.panResolutionRad(), 185.1428 / 3600 * M_PI / 180, 1e-12);
  ASSERT_TRUE(eventually([&] { return head.measured().has_value(); }));
  EXPECT_NEAR(head.measured()->angles.pan, 100 * head.panResolutionRad(), 1e-12);
  EXPECT_NEAR(head.measured()->angles.tilt, 50 * head.tiltResolutionRad(),
              1e-12);  // tilt direction -1
  // The unit's limits narrow the head's: pan 3090 positions = 158.9 deg > 1.5 rad default.
  EXPECT_DOUBLE_EQ(head.limits().panMax, 1.5);
  EXPECT_NEAR(head.limits().tiltMin, -604 * head.tiltResolutionRad(), 1e-12);
  head.shutdown();
  // Every scripted step matched in order; what came after the script (more
  // position queries, the final H) is reported as unexpected, never as a
  // mismatch of a scripted step.
  EXPECT_TRUE(s.scriptDone());
  for (const std::string& m : s.mismatches())
    EXPECT_EQ(m.rfind("unexpected write", 0), 0u) << m;
}

TEST(PtuHeadScripted, SilentUnitIsAClearError) {
  auto script = std::make_unique<ScriptedTransport>();
  script->expect("FT ", "");
  script->expect("FT ", "");
  PtuHeadOptions o;
  o.replyTimeout = 1ms;
  try {
    PtuHead head(std::move(script), o);
    FAIL() << "a silent PTU must not open";
  } catch (const horopter::Error& e) {
    EXPECT_NE(std::string(e.what()).find("does not answer 'FT'"), std::string::npos) << e.what();
  }
}

TEST(PtuHeadOnPty, FollowsCommandsOverThePty) {
  SimPtu sim;
  auto head = openHead(sim);
  EXPECT_FALSE(head->limits().hasVergence);
  head->command({0.2, -0.1, 0.3}, 1.0);
  ASSERT_TRUE(eventually([&] {
    auto m = head->measured();
    return m && std::abs(m->angles.pan - 0.2) < 0.001 && std::abs(m->angles.tilt + 0.1) < 0.001;
  })) << head->health().lastFault;
  EXPECT_EQ(sim.position(true), std::lround(0.2 / head->panResolutionRad()));
  EXPECT_EQ(sim.position(false), std::lround(0.1 / head->tiltResolutionRad()));  // tilt reversed
  EXPECT_EQ(head->measured()->angles.vergence, 0.0);
}

TEST(PtuHeadOnPty, HaltStopsWhereItIs) {
  SimPtu sim;
  auto head = openHead(sim);
  head->command({1.2, 0, 0}, 0.05);  // slow
  ASSERT_TRUE(eventually([&] { return std::abs(sim.position(true)) > 5; }));
  head->halt();
  ASSERT_TRUE(eventually([&] {
    const long a = sim.position(true);
    std::this_thread::sleep_for(50ms);
    return sim.position(true) == a;
  }));
  EXPECT_LT(head->measured()->angles.pan, 1.0);
}

TEST(PtuHeadOnPty, BadRepliesAreCountedAndTheLinkRecovers) {
  SimPtu sim;
  PtuHeadOptions o;
  o.replyTimeout = 50ms;
  auto head = openHead(sim, o);
  for (DeviceFault f : {DeviceFault::kCorruptChecksum, DeviceFault::kGarbage,
                        DeviceFault::kShortFrame, DeviceFault::kNoReply}) {
    const HeadHealth before = head->health();
    sim.injectFault(f, 1);
    ASSERT_TRUE(eventually([&] {
      const HeadHealth h = head->health();
      return h.corruptReplies + h.timeouts > before.corruptReplies + before.timeouts &&
             h.exchanges > before.exchanges + 2;
    })) << static_cast<int>(f)
        << ": " << head->health().lastFault;
  }
  EXPECT_TRUE(head->health().linkUp);
}

TEST(PtuHeadOnPty, DisconnectMidRunIsReported) {
  SimPtu sim;
  auto head = openHead(sim);
  sim.injectFault(DeviceFault::kDisconnect, 1);
  ASSERT_TRUE(eventually([&] { return !head->health().linkUp; }));
  EXPECT_FALSE(head->health().lastFault.empty());
}
