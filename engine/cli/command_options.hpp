// A command's own flags (--frames, --seed, --jobs, --out...), declared once
// in a table per command: flag, value name, range, unit, default and help.
// The parser and the --help lines both read the table, so what --help lists
// is what the command accepts, with the same ranges and defaults. The tuning
// structs' flags (stereo, detector, tracker...) keep their own tables
// (horopter/core/option_table.hpp); this is the same idea for the options
// that belong to one command.
#pragma once

#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "args.hpp"

namespace horopter::cli {

enum class OptionKind {
  Switch,   // present or not: --json
  Integer,  // a whole number within [min, max]
  Number,   // a finite number within [min, max]
  Text,     // any text: a path, a pattern, a list
  Choice,   // one of `choices`
  Heading,  // not an option: a section title in --help
};

struct CommandOption {
  OptionKind kind = OptionKind::Switch;
  const char* flag = "";      // "--frames"; for a Heading, its title
  const char* alias = "";     // another spelling, "-o"; "" for none
  const char* value = "";     // the value's name in --help: "N", "FILE"
  double min = 0, max = 0;    // Integer, Number: the allowed range, inclusive
  const char* unit = "";      // "s", "px", "" (a count)
  const char* fallback = "";  // the default, as it would be typed; "" = none (absent)
  // Or the default read from the library struct that owns it, so that it is
  // not restated here: e.g. [] { return defaultText(MovementModelParams{}.stay); }.
  std::string (*fallbackOf)() = nullptr;
  const char* choices = "";  // Choice: the allowed values, comma-separated
  const char* help = "";     // one line; wrapped by --help
};

// A struct member's default as a table's fallback text ("0.97", "15", "3").
std::string defaultText(double value);

// The default of an option as it would be typed: fallbackOf's or fallback's;
// "" when it has none.
std::string fallbackText(const CommandOption& o);

// The table's flags, taken out of `args` and checked: numbers parse strictly
// within their range, a choice must be one of its values. Every error is a
// UsageError naming the flag (and the range or the choices). The getters
// take a flag of the table; a flag the table lacks, or a getter of another
// kind, is a programming error (std::logic_error), as is a table whose
// default lies outside its range or choices, or that declares a flag twice.
class CommandOptions {
 public:
  CommandOptions(Args& args, std::span<const CommandOption> table);

  bool given(const std::string& flag) const;  // on the command line (any kind)
  bool on(const std::string& flag) const;     // a Switch
  // Integer / Number: the value given, else the default (the table's
  // `fallback`; one without a default must be asked through optional*).
  long long integer(const std::string& flag) const;
  double number(const std::string& flag) const;
  std::optional<long long> optionalInteger(const std::string& flag) const;
  std::optional<double> optionalNumber(const std::string& flag) const;
  // Text / Choice: the value given, else the default ("" when none).
  std::string text(const std::string& flag) const;
  std::optional<std::string> optionalText(const std::string& flag) const;

 private:
  const CommandOption& entry(const std::string& flag, std::initializer_list<OptionKind>) const;
  std::optional<std::string> raw(const CommandOption& o) const;

  std::span<const CommandOption> table_;
  std::vector<std::pair<std::string, std::string>> values_;  // flag, text as given
  std::set<std::string> switches_;
};

// The --help lines of the table: "  --flag V  help; min..max unit (default D)",
// wrapped; headings as "Title:".
std::string commandOptionsHelp(std::span<const CommandOption> table);

// Every flag and alias the table declares (for the tests).
std::vector<std::string> commandOptionFlags(std::span<const CommandOption> table);

}  // namespace horopter::cli
