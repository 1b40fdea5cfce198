#include "horopter/stereo_params.hpp"

#include <limits>
#include <string>

#include "horopter/error.hpp"

namespace horopter {

namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw Error(message);
}

std::string got(int v) {
  return ", got " + std::to_string(v);
}

}  // namespace

void validate(const StereoParams& p) {
  require(p.numDisparities > 0 && p.numDisparities % 16 == 0,
          "numDisparities must be a positive multiple of 16" + got(p.numDisparities));
  require(p.numDisparities <= 1024, "numDisparities must be at most 1024" + got(p.numDisparities));
  // Every output, the invalid marker included, must fit int16 in 1/16 px.
  const long lowest = (static_cast<long>(p.minDisparity) - 1) * kDisparityScale;
  const long highest = (static_cast<long>(p.minDisparity) + p.numDisparities) * kDisparityScale;
  require(lowest >= std::numeric_limits<std::int16_t>::min() &&
              highest <= std::numeric_limits<std::int16_t>::max(),
          "minDisparity + numDisparities must stay within -2047..2047 pixels so that 16 * "
          "disparity fits int16" +
              got(p.minDisparity));
  require(p.blockSize % 2 == 1 && p.blockSize >= 3 && p.blockSize <= 255,
          "blockSize must be odd and within 3..255" + got(p.blockSize));
  require(p.preFilterType == PreFilterType::None || p.preFilterType == PreFilterType::XSobel,
          "preFilterType must be None or XSobel");
  require(p.preFilterCap >= 1 && p.preFilterCap <= 63,
          "preFilterCap must be within 1..63" + got(p.preFilterCap));
  require(p.textureThreshold >= 0,
          "textureThreshold must be >= 0 (0 = off)" + got(p.textureThreshold));
  require(p.uniquenessRatio >= 0 && p.uniquenessRatio <= 1000,
          "uniquenessRatio must be within 0..1000 percent (0 = off)" + got(p.uniquenessRatio));
  require(p.speckleWindowSize >= 0,
          "speckleWindowSize must be >= 0 (0 = off)" + got(p.speckleWindowSize));
  require(p.speckleRange >= 0, "speckleRange must be >= 0 (1/16 px)" + got(p.speckleRange));
}

const char* toString(PreFilterType t) {
  return t == PreFilterType::None ? "none" : "xsobel";
}

PreFilterType parsePreFilterType(const std::string& s) {
  if (s == "none") return PreFilterType::None;
  if (s == "xsobel") return PreFilterType::XSobel;
  throw Error("unknown pre-filter type '" + s + "': use none or xsobel");
}

int effectiveMinValid(const MedianParams& m) {
  if (m.minValidToFill > 0) return m.minValidToFill;
  return m.kernelSize * m.kernelSize / 2 + 1;
}

void validate(const MedianParams& m) {
  require(m.kernelSize == 0 || m.kernelSize == 3 || m.kernelSize == 5,
          "median kernel size must be 0 (off), 3 or 5" + got(m.kernelSize));
  require(m.minValidToFill >= 0 && m.minValidToFill <= m.kernelSize * m.kernelSize,
          "median minValidToFill must be within 0..kernelSize^2 (0 = more than half)" +
              got(m.minValidToFill));
}

}  // namespace horopter
