// FLIR PTU ASCII commands and replies against the command reference
// (PTU-D300 User's Manual v2.19 §4.2-4.5; E Series Command Reference):
// "PP-2500 " -> "*", "PP " -> "* -2500" in terse mode, "! <message>" errors,
// "!P"/"!T" asynchronous limit hits; plus garbage and partial lines.
#include <gtest/gtest.h>

#include <numbers>

#include "horopter/core/error.hpp"
#include "horopter/hardware/ptu_protocol.hpp"

namespace ptu = horopter::hw::ptu;

TEST(PtuProtocol, CommandsMatchTheReference) {
  EXPECT_EQ(ptu::setPosition(ptu::Axis::kPan, -2500), "PP-2500 ");
  EXPECT_EQ(ptu::setPosition(ptu::Axis::kTilt, 300), "TP300 ");
  EXPECT_EQ(ptu::queryPosition(ptu::Axis::kPan), "PP ");
  EXPECT_EQ(ptu::setSpeed(ptu::Axis::kPan, 1000), "PS1000 ");
  EXPECT_EQ(ptu::queryResolution(ptu::Axis::kTilt), "TR ");
  EXPECT_EQ(ptu::queryMinPosition(ptu::Axis::kPan), "PN ");
  EXPECT_EQ(ptu::queryMaxPosition(ptu::Axis::kTilt), "TX ");
  EXPECT_EQ(ptu::halt(), "H ");
  EXPECT_EQ(ptu::await(), "A ");
  EXPECT_EQ(ptu::terseFeedback(), "FT ");
  EXPECT_EQ(ptu::echoOff(), "ED ");
}

TEST(PtuProtocol, RepliesParse) {
  auto ok = ptu::parseReply("*");
  EXPECT_EQ(ok.kind, ptu::ReplyKind::kOk);
  EXPECT_TRUE(ok.text.empty());
  auto q = ptu::parseReply("* -2500");
  EXPECT_EQ(ptu::parseInteger(q), -2500);
  auto res = ptu::parseReply("* 185.1428");
  EXPECT_NEAR(ptu::parseNumber(res), 185.1428, 1e-12);
  auto err = ptu::parseReply("! Maximum allowable Pan position is 3090");
  EXPECT_EQ(err.kind, ptu::ReplyKind::kError);
  EXPECT_THROW(ptu::parseNumber(err), horopter::Error);
  EXPECT_EQ(ptu::parseReply("!P").kind, ptu::ReplyKind::kLimitHit);
  EXPECT_EQ(ptu::parseReply("!T").text, "T");
}

TEST(PtuProtocol, GarbageAndNonNumbersAreErrors) {
  EXPECT_THROW(ptu::parseReply("\x13\x7f garbage"), horopter::Error);
  EXPECT_THROW(ptu::parseReply("   "), horopter::Error);
  EXPECT_THROW(ptu::parseNumber(ptu::parseReply("* 12abc")), horopter::Error);
  EXPECT_THROW(ptu::parseInteger(ptu::parseReply("* 1.5")), horopter::Error);
  EXPECT_THROW(ptu::parseNumber(ptu::parseReply("*")), horopter::Error);
}

TEST(PtuProtocol, LinesSplitOnCrOrLfAndWaitForTheTerminator) {
  std::string buffer = "* 12\r\n*\r* 3";
  EXPECT_EQ(ptu::takeLine(buffer), "* 12");
  EXPECT_EQ(ptu::takeLine(buffer), "*");
  EXPECT_EQ(ptu::takeLine(buffer), std::nullopt);
  buffer += "4\n";
  EXPECT_EQ(ptu::takeLine(buffer), "* 34");
  EXPECT_TRUE(buffer.empty());
}

TEST(PtuProtocol, ResolutionArcSecondsToRadians) {
  // 185.1428 arc-seconds per position (the PTU-D46's pan resolution in half-step mode).
  EXPECT_NEAR(ptu::arcSecondsToRadians(185.1428), 185.1428 / 3600 * std::numbers::pi / 180, 1e-15);
  EXPECT_NEAR(ptu::arcSecondsToRadians(3600), std::numbers::pi / 180, 1e-15);
}

// from_chars accepts "inf" and "nan"; a cast of inf (or 1e300) to long is undefined.
TEST(PtuProtocol, NonFiniteAndHugeNumbersAreErrors) {
  for (const char* text : {"* inf", "* -inf", "* nan", "* -nan", "* infinity", "* INF"}) {
    EXPECT_THROW(ptu::parseNumber(ptu::parseReply(text)), horopter::Error) << text;
    EXPECT_THROW(ptu::parseInteger(ptu::parseReply(text)), horopter::Error) << text;
  }
  EXPECT_THROW(ptu::parseNumber(ptu::parseReply("* 1e400")), horopter::Error);
  for (const char* text : {"* 1e300", "* 9223372036854775807", "* -9.3e18", "* 2147483648"})
    EXPECT_THROW(ptu::parseInteger(ptu::parseReply(text)), horopter::Error) << text;
  EXPECT_EQ(ptu::parseInteger(ptu::parseReply("* 2147483647")), 2147483647L);
  EXPECT_EQ(ptu::parseInteger(ptu::parseReply("* -2147483648")), -2147483648L);
}
