// The interaction layer's tuning options, declared once in tables: every
// default lies in its range, names and flags are unique, and the objects
// that take the options refuse a value outside the range with its name.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "horopter/core/error.hpp"
#include "horopter/interaction/detection.hpp"
#include "horopter/interaction/godfather.hpp"
#include "horopter/interaction/head_control.hpp"
#include "horopter/interaction/tracking.hpp"
#include "test_support.hpp"

namespace horopter {
namespace {

using test::errorOf;

template <class Params>
void expectWellFormed(std::span<const NumberOption<Params>> table, std::set<std::string>& flags) {
  const Params defaults;
  std::set<std::string> names;
  ASSERT_FALSE(table.empty());
  for (const NumberOption<Params>& o : table) {
    SCOPED_TRACE(o.name);
    EXPECT_TRUE(names.insert(o.name).second) << "name used twice";
    EXPECT_TRUE(flags.insert(o.flag).second) << "flag used twice across the tables";
    EXPECT_EQ(std::string(o.flag).rfind("--", 0), 0u);
    EXPECT_LE(o.min, o.max);
    EXPECT_GE(o.get(defaults), o.min);
    EXPECT_LE(o.get(defaults), o.max);
    EXPECT_FALSE(std::string(o.help).empty());
    if (o.integer()) {
      EXPECT_EQ(o.min, std::floor(o.min));
      EXPECT_EQ(o.max, std::floor(o.max));
    }
  }
  EXPECT_NO_THROW(checkRanges(table, defaults));
}

TEST(TuningOptions, EveryTableIsWellFormedAndFlagsAreUnique) {
  std::set<std::string> flags;
  expectWellFormed(detectorOptions(), flags);
  expectWellFormed(electionOptions(), flags);
  expectWellFormed(trackerOptions(), flags);
  expectWellFormed(headControlOptions(), flags);
}

// For each entry: just past either end of its range, and NaN for the
// numbers, must be refused by checkRanges with the option's name and range.
template <class Params>
void expectRangesEnforced(std::span<const NumberOption<Params>> table) {
  for (const NumberOption<Params>& o : table) {
    SCOPED_TRACE(o.name);
    const double step = o.integer() ? 1 : 1e-6 * std::max(1.0, o.max - o.min);
    std::vector<double> bad = {o.min - step, o.max + step};
    if (!o.integer()) bad.push_back(std::numeric_limits<double>::quiet_NaN());
    for (double v : bad) {
      Params p;
      o.set(p, v);
      const std::string message = errorOf([&] { checkRanges(table, p); });
      EXPECT_NE(message.find(std::string(o.name) + " must be within"), std::string::npos)
          << v << ": " << message;
    }
  }
}

TEST(TuningOptions, OutOfRangeValuesAreRefusedWithTheirNames) {
  expectRangesEnforced(detectorOptions());
  expectRangesEnforced(electionOptions());
  expectRangesEnforced(trackerOptions());
  expectRangesEnforced(headControlOptions());
}

TEST(TuningOptions, TheObjectsCheckTheirTables) {
  ElectionOptions e;
  e.releaseS = -1;
  EXPECT_NE(errorOf([&] { GodfatherElection{e}; }).find("releaseS must be within 0..3600 s"),
            std::string::npos);
  TrackerOptions t;
  t.blindMinScore = 1.5;
  EXPECT_NE(errorOf([&] { BodyTracker{t}; }).find("blindMinScore must be within -1..1"),
            std::string::npos);
  HeadControlOptions h;
  h.maxHandShiftFraction = 0.6;
  EXPECT_NE(errorOf([&] { validate(h); }).find("maxHandShiftFraction must be within 0..0.5"),
            std::string::npos);
  DetectorOptions d;
  d.fullSearchEvery = 0;
  EXPECT_NE(errorOf([&] { Detector{d}; }).find("fullSearchEvery must be within 1..1000"),
            std::string::npos);
}

// The options outside the tables are internal gates (no flag, no Python
// keyword): their objects still check them.
TEST(TuningOptions, InternalGatesStayChecked) {
  ElectionOptions e;
  e.candidateGraceS = std::nan("");
  EXPECT_NE(errorOf([&] { GodfatherElection{e}; }).find("candidate grace"), std::string::npos);
  e = ElectionOptions{};
  e.electS = std::nan("");
  EXPECT_NE(errorOf([&] { GodfatherElection{e}; }).find("electS must be within 0..3600 s"),
            std::string::npos);
  TrackerOptions t;
  t.coastS = -1;
  EXPECT_NE(errorOf([&] { BodyTracker{t}; }).find("tracker coast time"), std::string::npos);
  t = TrackerOptions{};
  t.blindValidFraction = 2;
  EXPECT_NE(errorOf([&] { BodyTracker{t}; }).find("tracker blind following"), std::string::npos);
}

}  // namespace
}  // namespace horopter
