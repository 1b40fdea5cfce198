#include "args.hpp"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <thread>

#include "horopter/core/error.hpp"
#include "horopter/core/option_table.hpp"

namespace horopter::cli {

Args::Args(int argc, char** argv, int first) {
  for (int i = first; i < argc; ++i)
    args_.emplace_back(argv[i]);
}

void Args::noteAsked(const std::string& name) {
  if (std::find(asked_.begin(), asked_.end(), name) == asked_.end()) asked_.push_back(name);
}

bool Args::flag(const std::string& name) {
  noteAsked(name);
  for (auto it = args_.begin(); it != args_.end(); ++it) {
    if (*it == name) {
      args_.erase(it);
      return true;
    }
  }
  return false;
}

std::optional<std::string> Args::value(const std::string& name) {
  noteAsked(name);
  for (auto it = args_.begin(); it != args_.end(); ++it) {
    if (*it == name) {
      if (it + 1 == args_.end()) throw UsageError(name + " needs a value");
      std::string v = *(it + 1);
      args_.erase(it, it + 2);
      return v;
    }
    if (it->rfind(name + "=", 0) == 0) {
      std::string v = it->substr(name.size() + 1);
      args_.erase(it);
      return v;
    }
  }
  return std::nullopt;
}

int Args::intValue(const std::string& name, int fallback, int min, int max) {
  const auto v = value(name);
  return v ? static_cast<int>(asUsageError([&] { return parseInteger(*v, name, min, max); }))
           : fallback;
}

double Args::doubleValue(const std::string& name, double fallback, double min, double max) {
  return optionalDouble(name, min, max).value_or(fallback);
}

std::optional<double> Args::optionalDouble(const std::string& name, double min, double max) {
  const auto v = value(name);
  if (!v) return std::nullopt;
  return asUsageError([&] { return parseNumber(*v, name, min, max); });
}

std::string Args::stringValue(const std::string& name, const std::string& fallback) {
  const auto v = value(name);
  return v ? *v : fallback;
}

std::vector<std::string> Args::positionals() {
  std::vector<std::string> out, rest;
  for (const auto& a : args_) {
    if (a.rfind("--", 0) == 0 || (a.size() == 2 && a[0] == '-' && a != "-")) {
      rest.push_back(a);
    } else {
      out.push_back(a);
    }
  }
  args_ = rest;
  return out;
}

void Args::finish(const std::string& command) const {
  if (const char* list = std::getenv("HOROPTER_LIST_FLAGS"); list && *list) {
    for (const std::string& name : asked_)
      if (name != "--help" && name != "-h") std::cout << name << "\n";
    std::cout.flush();
    std::exit(0);
  }
  if (args_.empty()) return;
  throw UsageError("unknown argument '" + args_.front() + "' for '" + command + "': see horopter " +
                   command + " --help");
}

StereoParams parseStereoFlags(Args& args, StereoParams p) {
  for (const IntOption<StereoParams>& o : stereoOptions())
    p.*o.member = args.intValue(o.flag, p.*o.member, o.min, o.max);
  if (auto v = args.value("--pre-filter-type"))
    p.preFilterType = asUsageError([&] { return parsePreFilterType(*v); });
  asUsageError([&] { validate(p); });
  return p;
}

MedianParams parseMedianFlags(Args& args, MedianParams m) {
  for (const IntOption<MedianParams>& o : medianOptions())
    m.*o.member = args.intValue(o.flag, m.*o.member, o.min, o.max);
  asUsageError([&] { validate(m); });
  return m;
}

ImageSize parseImageSize(const std::string& text, const std::string& option, ImageSize min,
                         ImageSize max) {
  const std::string expected = option + " takes WxH within " + std::to_string(min.width) + "x" +
                               std::to_string(min.height) + ".." + std::to_string(max.width) + "x" +
                               std::to_string(max.height) + ", got '" + text + "'";
  const auto x = text.find('x');
  if (x == std::string::npos) throw UsageError(expected);
  try {
    return {static_cast<int>(parseInteger(text.substr(0, x), option, min.width, max.width)),
            static_cast<int>(parseInteger(text.substr(x + 1), option, min.height, max.height))};
  } catch (const Error&) {
    throw UsageError(expected);
  }
}

int parseThreads(Args& args, int fallback) {
  return resolveThreads(args.intValue("--threads", fallback, 0, 256));
}

namespace {

// "  --flag N   help, unit, min..max (default D)", from an option's entry.
template <class Params>
void optionHelp(std::ostringstream& o, const IntOption<Params>& option, const Params& defaults) {
  std::string flag = std::string("  ") + option.flag + " N";
  flag.resize(std::max<std::size_t>(flag.size() + 2, 27), ' ');
  o << flag << option.help << "; " << option.min << ".." << option.max
    << (*option.unit ? std::string(" ") + option.unit : std::string()) << " (default "
    << defaults.*option.member << ")\n";
}

}  // namespace

std::string stereoFlagsHelp(const StereoParams& p, const MedianParams& m,
                            const std::string& threadsDefault) {
  std::ostringstream o;
  o << "Stereo parameters (the names of cv::StereoBM; disparities are int16 in 1/16 px):\n";
  for (const IntOption<StereoParams>& option : stereoOptions())
    optionHelp(o, option, p);
  o << "  --pre-filter-type T      normalized (StereoBM's PREFILTER_NORMALIZED_RESPONSE, window "
       "--pre-filter-size), xsobel or none (default "
    << toString(p.preFilterType) << ")\n";
  for (const IntOption<MedianParams>& option : medianOptions())
    optionHelp(o, option, m);
  o << "  --threads N              threads for the front end's stripes, 1..256, 0: all (default: "
    << (threadsDefault.empty() ? "all, " + std::to_string(resolveThreads(FrontendDefaults::threads))
                               : threadsDefault)
    << ")\n";
  return o.str();
}

std::string optionHelpLine(const std::string& flag, const std::string& help, double min, double max,
                           const std::string& unit, double fallback) {
  std::ostringstream range;
  range << "; " << min << ".." << max << (unit.empty() ? "" : " " + unit) << " (default "
        << fallback << ")";
  return helpEntry(flag, help + range.str());
}

std::string helpEntry(const std::string& flag, const std::string& text) {
  constexpr std::size_t kIndent = 21, kWidth = 88;
  std::istringstream words(text);
  std::string line = "  " + flag, out, word;
  // The flag takes the first line alone when it comes within two spaces of
  // the text's column.
  if (line.size() + 2 > kIndent) {
    out += line + "\n";
    line.clear();
  }
  line.resize(kIndent, ' ');
  bool first = true;
  while (words >> word) {
    if (!first && line.size() + 1 + word.size() > kWidth) {
      out += line + "\n";
      line = std::string(kIndent, ' ');
      first = true;
    }
    line += (first ? "" : " ") + word;
    first = false;
  }
  return out + line + "\n";
}

}  // namespace horopter::cli
