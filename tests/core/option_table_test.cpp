// The options declared once: strict number parsing, and every table entry
// checked by validate() with its own name and range.
#include <gtest/gtest.h>

#include <climits>
#include <set>
#include <string>

#include "horopter/core/error.hpp"
#include "horopter/core/option_table.hpp"
#include "horopter/kernels/stereo_params.hpp"
#include "test_support.hpp"

namespace horopter {
namespace {

using test::errorOf;

TEST(OptionTable, IntegersParseWholeAndInRangeOnly) {
  EXPECT_EQ(parseInteger("42", "--n", 0, 100), 42);
  EXPECT_EQ(parseInteger("-7", "--n", -10, 10), -7);
  EXPECT_EQ(parseInteger("0", "--n", 0, 0), 0);
  for (const char* bad : {"", "abc", "2junk", "4 ", " 4", "+4", "4.0", "1e3", "0x10", "nan", "101",
                          "-1", "99999999999999999999"}) {
    const std::string message = errorOf([&] { parseInteger(bad, "--n", 0, 100); });
    EXPECT_NE(message.find("--n needs an integer within 0..100"), std::string::npos) << bad;
    EXPECT_NE(message.find(std::string("'") + bad + "'"), std::string::npos) << bad;
  }
}

TEST(OptionTable, NumbersAreFiniteWholeAndInRange) {
  EXPECT_DOUBLE_EQ(parseNumber("1.5", "--x", 0, 2), 1.5);
  EXPECT_DOUBLE_EQ(parseNumber("-0.25", "--x", -1, 1), -0.25);
  EXPECT_DOUBLE_EQ(parseNumber("2e-1", "--x", 0, 1), 0.2);
  for (const char* bad :
       {"", "abc", "1.5junk", "nan", "NaN", "inf", "-inf", "0x1p3", "1e999", "3", "-2", " 1"}) {
    const std::string message = errorOf([&] { parseNumber(bad, "--x", -1, 2); });
    EXPECT_NE(message.find("--x needs a number within -1..2"), std::string::npos) << bad;
  }
}

TEST(OptionTable, EveryStereoOptionHasADefaultInRangeAndAnUniqueNameAndFlag) {
  const StereoParams defaults;
  std::set<std::string> names, flags;
  for (const IntOption<StereoParams>& o : stereoOptions()) {
    EXPECT_LE(o.min, defaults.*o.member) << o.name;
    EXPECT_GE(o.max, defaults.*o.member) << o.name;
    EXPECT_TRUE(names.insert(o.name).second) << o.name;
    EXPECT_TRUE(flags.insert(o.flag).second) << o.flag;
    EXPECT_EQ(std::string(o.flag).rfind("--", 0), 0u) << o.flag;
    EXPECT_GT(std::string(o.help).size(), 5u) << o.name;
  }
  // Every int member of StereoParams is in the table (11 of them, the
  // twelfth member being the pre-filter's type).
  EXPECT_EQ(stereoOptions().size(), 11u);
  EXPECT_NO_THROW(validate(defaults));
}

TEST(OptionTable, ValidateNamesEachOptionOutOfItsRange) {
  for (const IntOption<StereoParams>& o : stereoOptions()) {
    for (const long long v :
         {static_cast<long long>(o.min) - 1, static_cast<long long>(o.max) + 1}) {
      if (v < INT_MIN || v > INT_MAX) continue;
      StereoParams p;
      p.*o.member = static_cast<int>(v);
      if (o.member == &StereoParams::blockSize && v % 2 == 0) p.*o.member += v < o.min ? -1 : 1;
      const std::string message = errorOf([&] { validate(p); });
      EXPECT_NE(message.find(o.name), std::string::npos) << o.name << " = " << v << ": " << message;
    }
  }
  for (const IntOption<MedianParams>& o : medianOptions()) {
    MedianParams m;
    m.*o.member = o.max + 1;
    EXPECT_NE(errorOf([&] { validate(m); }).find(o.name), std::string::npos) << o.name;
  }
}

TEST(OptionTable, RulesAcrossOptionsStillHold) {
  StereoParams p;
  p.numDisparities = 40;  // in range, not a multiple of 16
  EXPECT_NE(errorOf([&] { validate(p); }).find("multiple of 16"), std::string::npos);
  p = StereoParams{};
  p.blockSize = 8;
  EXPECT_NE(errorOf([&] { validate(p); }).find("blockSize must be odd"), std::string::npos);
  p = StereoParams{};
  p.minDisparity = 2000;  // 2000 + 64 does not fit int16 in 1/16 px
  EXPECT_NE(errorOf([&] { validate(p); }).find("fits int16"), std::string::npos);
  p = StereoParams{};
  p.leftBand = p.numDisparities + 16;  // in 0..1024, more than the range has
  EXPECT_NE(errorOf([&] { validate(p); }).find("leftBand must be within 0..numDisparities"),
            std::string::npos);
  p.leftBand = p.numDisparities;
  EXPECT_NO_THROW(validate(p));
  MedianParams m;
  m.kernelSize = 3;
  m.minValidToFill = 10;  // more than the 3x3 window
  EXPECT_NE(errorOf([&] { validate(m); }).find("minValidToFill"), std::string::npos);
  m = MedianParams{};
  m.kernelSize = 4;
  EXPECT_NE(errorOf([&] { validate(m); }).find("0 (off), 3 or 5"), std::string::npos);
}

}  // namespace
}  // namespace horopter
