// A small command-line parser: flags are taken out of the list by name, and
// whatever is left over is an error, so a typo never passes silently.
#pragma once

#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "horopter/core/option_table.hpp"
#include "horopter/kernels/stereo_params.hpp"
#include "horopter/vision/frontend.hpp"

namespace horopter::cli {

// A wrong command line: an unknown flag, a value out of range or malformed,
// a missing or contradictory option, a file an option names that is missing.
// Thrown before a command does any work; `horopter` exits with 2 for it (1
// for an error during the work).
class UsageError : public Error {
 public:
  using Error::Error;
};

// Runs `parse` and turns a horopter::Error it throws (a library's check of
// an option's value) into a UsageError with the same message.
template <class F>
auto asUsageError(F&& parse) -> decltype(parse()) {
  try {
    return parse();
  } catch (const UsageError&) {
    throw;
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
}

class Args {
 public:
  Args(int argc, char** argv, int first);

  // True (and removed) if `name` is present.
  bool flag(const std::string& name);
  // The value after `name` ("--x 3" or "--x=3"), removed; nullopt if absent.
  std::optional<std::string> value(const std::string& name);
  // Numbers parse strictly (horopter/core/option_table.hpp): "2junk", "abc", "nan"
  // and values outside [min, max] are errors naming the flag.
  int intValue(const std::string& name, int fallback, int min = -1000000000, int max = 1000000000);
  double doubleValue(const std::string& name, double fallback, double min = -1e300,
                     double max = 1e300);
  std::optional<double> optionalDouble(const std::string& name, double min = -1e300,
                                       double max = 1e300);
  std::string stringValue(const std::string& name, const std::string& fallback);
  // The remaining positional arguments (those not starting with "--"), removed.
  std::vector<std::string> positionals();
  // Throws UsageError if anything is left: an unknown flag or extra argument.
  // With HOROPTER_LIST_FLAGS=1 in the environment it prints instead every
  // flag the command asked for (but --help and -h), one a line, and exits 0
  // before any work: tests/cli/help_lists_every_flag.sh compares that with
  // what --help lists.
  void finish(const std::string& command) const;

 private:
  void noteAsked(const std::string& name);

  std::vector<std::string> args_;
  std::vector<std::string> asked_;  // every flag name asked for, in order
};

// "WxH" with each side within its range; anything else ("640x480junk",
// "640 x 480", "-1x5") is a UsageError naming `option`.
struct ImageSize {
  int width = 0, height = 0;
};
ImageSize parseImageSize(const std::string& text, const std::string& option, ImageSize min,
                         ImageSize max);

// The stereo flags every command shares (kebab-case names of StereoParams).
StereoParams parseStereoFlags(Args& args, StereoParams defaults);
MedianParams parseMedianFlags(Args& args, MedianParams defaults);
// --threads, 1..256 or 0 (all hardware threads); `fallback` when absent
// (by default FrontendDefaults::threads, all of them). Returns the resolved count.
int parseThreads(Args& args, int fallback = FrontendDefaults::threads);
// Help text for those flags, with the defaults; `threadsDefault` says what
// --threads defaults to where the command's fallback is not all cores.
std::string stereoFlagsHelp(const StereoParams& defaults, const MedianParams& median,
                            const std::string& threadsDefault = "");

// The flags of a tuning table (detectorOptions(), trackerOptions()...), each
// parsed strictly within its range; absent flags keep p's values.
template <class Params>
Params parseOptionFlags(Args& args, std::span<const NumberOption<Params>> table, Params p) {
  for (const NumberOption<Params>& o : table) {
    const auto v = args.value(o.flag);
    if (!v) continue;
    asUsageError([&] {
      if (o.integer())
        o.set(p,
              static_cast<double>(parseInteger(*v, o.flag, static_cast<long long>(std::ceil(o.min)),
                                               static_cast<long long>(std::floor(o.max)))));
      else
        o.set(p, parseNumber(*v, o.flag, o.min, o.max));
    });
  }
  return p;
}

// One help entry: "  FLAG" and `text` beside it, wrapped to 88 columns.
std::string helpEntry(const std::string& flag, const std::string& text);

// One help entry, "  --flag X  help; min..max unit (default D)", wrapped.
std::string optionHelpLine(const std::string& flag, const std::string& help, double min, double max,
                           const std::string& unit, double fallback);

// The help of a tuning table's flags, with p's values as the defaults.
template <class Params>
std::string optionFlagsHelp(std::span<const NumberOption<Params>> table, const Params& p) {
  std::string out;
  for (const NumberOption<Params>& o : table)
    out += optionHelpLine(std::string(o.flag) + (o.integer() ? " N" : " X"), o.help, o.min, o.max,
                          o.unit, o.get(p));
  return out;
}

}  // namespace horopter::cli
