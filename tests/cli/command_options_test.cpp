// The command option tables (engine/cli/command_options.hpp): what the
// parser takes and refuses, and the --help lines it shares with it.
#include "command_options.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace horopter::cli {
namespace {

constexpr CommandOption kTable[] = {
    {.kind = OptionKind::Heading, .flag = "Input"},
    {.kind = OptionKind::Integer,
     .flag = "--frames",
     .value = "N",
     .min = 1,
     .max = 1000,
     .fallback = "300",
     .help = "frames to run"},
    {.kind = OptionKind::Number,
     .flag = "--fps",
     .value = "F",
     .min = 0,
     .max = 240,
     .unit = "frames/s",
     .help = "camera rate"},
    {.kind = OptionKind::Choice,
     .flag = "--scope",
     .value = "S",
     .fallback = "region",
     .choices = "region,full,both",
     .help = "where to detect"},
    {.kind = OptionKind::Text,
     .flag = "--out",
     .alias = "-o",
     .value = "DIR",
     .fallback = "out",
     .help = "output folder"},
    {.kind = OptionKind::Switch, .flag = "--json", .help = "print JSON"},
};

// Args from a list of words (argv[0] is the program).
struct Line {
  std::vector<std::string> words;
  std::vector<char*> argv;
  explicit Line(std::vector<std::string> w) : words(std::move(w)) {
    argv.push_back(const_cast<char*>("horopter"));
    for (std::string& s : words)
      argv.push_back(s.data());
  }
  Args args() { return Args(static_cast<int>(argv.size()), argv.data(), 1); }
};

std::string usageError(std::vector<std::string> words) {
  Line line(std::move(words));
  Args args = line.args();
  try {
    const CommandOptions o(args, kTable);
    args.finish("test");
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

TEST(CommandOptions, TakesValuesAndFallsBackToTheTablesDefaults) {
  Line line({"--frames", "12", "-o", "here", "--json", "--scope=full"});
  Args args = line.args();
  const CommandOptions o(args, kTable);
  EXPECT_NO_THROW(args.finish("test"));
  EXPECT_EQ(o.integer("--frames"), 12);
  EXPECT_EQ(o.text("--out"), "here");
  EXPECT_TRUE(o.on("--json"));
  EXPECT_EQ(o.text("--scope"), "full");
  EXPECT_FALSE(o.optionalNumber("--fps").has_value());
  EXPECT_FALSE(o.given("--fps"));

  Line empty({});
  Args none = empty.args();
  const CommandOptions d(none, kTable);
  EXPECT_EQ(d.integer("--frames"), 300);
  EXPECT_EQ(d.text("--out"), "out");
  EXPECT_EQ(d.text("--scope"), "region");
  EXPECT_FALSE(d.on("--json"));
  EXPECT_FALSE(d.given("--frames"));
}

TEST(CommandOptions, MalformedAndOutOfRangeValuesNameTheFlagAndRange) {
  EXPECT_EQ(usageError({"--frames", "abc"}), "--frames needs an integer within 1..1000, got 'abc'");
  EXPECT_EQ(usageError({"--frames", "2junk"}),
            "--frames needs an integer within 1..1000, got '2junk'");
  EXPECT_EQ(usageError({"--frames", "0"}), "--frames needs an integer within 1..1000, got '0'");
  EXPECT_EQ(usageError({"--fps", "nan"}), "--fps needs a number within 0..240, got 'nan'");
  EXPECT_EQ(usageError({"--fps", "1e9"}), "--fps needs a number within 0..240, got '1e9'");
  EXPECT_EQ(usageError({"--scope", "there"}), "--scope takes region, full or both, got 'there'");
  EXPECT_EQ(usageError({"--frames"}), "--frames needs a value");
  EXPECT_EQ(usageError({"--frames", "2", "--frames", "3"}), "--frames is given more than once");
  EXPECT_EQ(usageError({"-o", "a", "--out", "b"}), "--out is given more than once");
  EXPECT_NE(usageError({"--frobnicate"}).find("unknown argument '--frobnicate'"),
            std::string::npos);
  EXPECT_EQ(usageError({"--frames", "1000", "--fps", "0"}), "");
}

TEST(CommandOptions, ReadingAFlagTheTableLacksIsAProgrammingError) {
  Line line({});
  Args args = line.args();
  const CommandOptions o(args, kTable);
  EXPECT_THROW(o.integer("--trials"), std::logic_error);
  EXPECT_THROW(o.text("--frames"), std::logic_error);  // an integer read as text
  EXPECT_THROW(o.number("--fps"), std::logic_error);   // no default: optionalNumber
}

TEST(CommandOptions, AMalformedTableIsAProgrammingError) {
  constexpr CommandOption kDefaultOutOfRange[] = {{.kind = OptionKind::Integer,
                                                   .flag = "--n",
                                                   .value = "N",
                                                   .min = 1,
                                                   .max = 9,
                                                   .fallback = "0"}};
  constexpr CommandOption kDefaultNotAChoice[] = {
      {.kind = OptionKind::Choice, .flag = "--c", .value = "C", .fallback = "z", .choices = "a,b"}};
  constexpr CommandOption kTwice[] = {
      {.kind = OptionKind::Switch, .flag = "--x"},
      {.kind = OptionKind::Text, .flag = "--y", .alias = "--x", .value = "Y"}};
  Line line({});
  Args args = line.args();
  EXPECT_THROW(CommandOptions(args, kDefaultOutOfRange), std::logic_error);
  EXPECT_THROW(CommandOptions(args, kDefaultNotAChoice), std::logic_error);
  EXPECT_THROW(CommandOptions(args, kTwice), std::logic_error);
  EXPECT_NO_THROW(CommandOptions(args, kTable));
}

// A default read from the struct that owns it (fallbackOf) is parsed,
// checked and listed like one written in the table.
struct Owner {
  double rate = 12.5;
};

TEST(CommandOptions, ADefaultReadFromItsStructActsAsTheTablesOwn) {
  constexpr CommandOption kFromStruct[] = {{.kind = OptionKind::Number,
                                            .flag = "--rate",
                                            .value = "R",
                                            .min = 0,
                                            .max = 100,
                                            .fallbackOf = [] { return defaultText(Owner{}.rate); },
                                            .help = "a rate"}};
  Line line({});
  Args args = line.args();
  const CommandOptions o(args, kFromStruct);
  EXPECT_EQ(o.number("--rate"), 12.5);
  EXPECT_NE(commandOptionsHelp(kFromStruct).find("(default 12.5)"), std::string::npos);
  constexpr CommandOption kOutOfRange[] = {
      {.kind = OptionKind::Number,
       .flag = "--rate",
       .value = "R",
       .min = 0,
       .max = 10,
       .fallbackOf = [] { return defaultText(Owner{}.rate); }}};
  constexpr CommandOption kTwoDefaults[] = {{.kind = OptionKind::Number,
                                             .flag = "--rate",
                                             .value = "R",
                                             .min = 0,
                                             .max = 100,
                                             .fallback = "1",
                                             .fallbackOf = [] { return std::string("2"); }}};
  EXPECT_THROW(CommandOptions(args, kOutOfRange), std::logic_error);
  EXPECT_THROW(CommandOptions(args, kTwoDefaults), std::logic_error);
}

TEST(CommandOptions, HelpListsEveryFlagWithItsRangeAndDefault) {
  const std::string help = commandOptionsHelp(kTable);
  EXPECT_NE(help.find("Input:\n"), std::string::npos);
  EXPECT_NE(help.find("  --frames N"), std::string::npos);
  EXPECT_NE(help.find("frames to run; 1..1000 (default 300)"), std::string::npos);
  EXPECT_NE(help.find("camera rate; 0..240 frames/s\n"), std::string::npos);
  EXPECT_NE(help.find("where to detect; region, full or both (default region)"), std::string::npos);
  EXPECT_NE(help.find("  -o, --out DIR"), std::string::npos);
  EXPECT_NE(help.find("  --json "), std::string::npos);
  for (const std::string& flag : commandOptionFlags(kTable))
    EXPECT_NE(help.find(flag), std::string::npos) << flag;
}

}  // namespace
}  // namespace horopter::cli
