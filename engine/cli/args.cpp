#include "args.hpp"

#include <algorithm>
#include <sstream>
#include <thread>

#include "horopter/error.hpp"

namespace horopter::cli {

Args::Args(int argc, char** argv, int first) {
  for (int i = first; i < argc; ++i)
    args_.emplace_back(argv[i]);
}

bool Args::flag(const std::string& name) {
  for (auto it = args_.begin(); it != args_.end(); ++it) {
    if (*it == name) {
      args_.erase(it);
      return true;
    }
  }
  return false;
}

std::optional<std::string> Args::value(const std::string& name) {
  for (auto it = args_.begin(); it != args_.end(); ++it) {
    if (*it == name) {
      if (it + 1 == args_.end()) throw Error(name + " needs a value");
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

int Args::intValue(const std::string& name, int fallback) {
  const auto v = value(name);
  if (!v) return fallback;
  try {
    std::size_t used = 0;
    const long n = std::stol(*v, &used);
    if (used != v->size() || n < -1000000000L || n > 1000000000L) throw std::invalid_argument("");
    return static_cast<int>(n);
  } catch (const std::exception&) {
    throw Error(name + " needs an integer, got '" + *v + "'");
  }
}

double Args::doubleValue(const std::string& name, double fallback) {
  return optionalDouble(name).value_or(fallback);
}

std::optional<double> Args::optionalDouble(const std::string& name) {
  const auto v = value(name);
  if (!v) return std::nullopt;
  try {
    std::size_t used = 0;
    const double d = std::stod(*v, &used);
    if (used != v->size()) throw std::invalid_argument("");
    return d;
  } catch (const std::exception&) {
    throw Error(name + " needs a number, got '" + *v + "'");
  }
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
  if (args_.empty()) return;
  throw Error("unknown argument '" + args_.front() + "' for '" + command + "': see horopter " +
              command + " --help");
}

StereoParams parseStereoFlags(Args& args, StereoParams p) {
  p.minDisparity = args.intValue("--min-disparity", p.minDisparity);
  p.numDisparities = args.intValue("--num-disparities", p.numDisparities);
  p.blockSize = args.intValue("--block-size", p.blockSize);
  if (auto v = args.value("--pre-filter-type")) p.preFilterType = parsePreFilterType(*v);
  p.preFilterCap = args.intValue("--pre-filter-cap", p.preFilterCap);
  p.textureThreshold = args.intValue("--texture-threshold", p.textureThreshold);
  p.uniquenessRatio = args.intValue("--uniqueness-ratio", p.uniquenessRatio);
  p.disp12MaxDiff = args.intValue("--disp12-max-diff", p.disp12MaxDiff);
  p.speckleWindowSize = args.intValue("--speckle-window-size", p.speckleWindowSize);
  p.speckleRange = args.intValue("--speckle-range", p.speckleRange);
  validate(p);
  return p;
}

MedianParams parseMedianFlags(Args& args, MedianParams m) {
  m.kernelSize = args.intValue("--median-size", m.kernelSize);
  m.minValidToFill = args.intValue("--median-min-valid", m.minValidToFill);
  validate(m);
  return m;
}

int parseThreads(Args& args, int fallback) {
  if (fallback < 1) fallback = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int threads = args.intValue("--threads", fallback);
  if (threads < 1 || threads > 256)
    throw Error("--threads must be within 1..256, got " + std::to_string(threads));
  return threads;
}

std::string stereoFlagsHelp(const StereoParams& p, const MedianParams& m) {
  std::ostringstream o;
  o << "Stereo parameters (the names of cv::StereoBM; disparities are int16 in 1/16 px):\n"
    << "  --min-disparity N        smallest disparity searched, px (default " << p.minDisparity
    << ")\n"
    << "  --num-disparities N      search range, a positive multiple of 16 (default "
    << p.numDisparities << ")\n"
    << "  --block-size N           odd matching window side, 3..255 (default " << p.blockSize
    << ")\n"
    << "  --pre-filter-type T      xsobel or none (default " << toString(p.preFilterType) << ")\n"
    << "  --pre-filter-cap N       x-Sobel clip, 1..63 (default " << p.preFilterCap << ")\n"
    << "  --texture-threshold N    least window texture, 0 = off (default " << p.textureThreshold
    << ")\n"
    << "  --uniqueness-ratio N     percent margin of the winner, 0 = off (default "
    << p.uniquenessRatio << ")\n"
    << "  --disp12-max-diff N      left-right check tolerance, px; -1 = off (default "
    << p.disp12MaxDiff << ")\n"
    << "  --speckle-window-size N  largest blob removed, px; 0 = off (default "
    << p.speckleWindowSize << ")\n"
    << "  --speckle-range N        largest step inside a blob, 1/16 px (default " << p.speckleRange
    << ")\n"
    << "  --median-size N          hole-filling median: 0 (off), 3 or 5 (default " << m.kernelSize
    << ")\n"
    << "  --median-min-valid N     valid neighbours needed to fill a hole; 0 = more than half\n"
    << "                           the window (default " << m.minValidToFill << ")\n"
    << "  --threads N              threads for the front end's stripes (default: all "
    << std::max(1u, std::thread::hardware_concurrency()) << ")\n";
  return o.str();
}

}  // namespace horopter::cli
