#include "horopter/kernels/stereo_params.hpp"

#include <limits>
#include <string>

#include "horopter/core/error.hpp"

namespace horopter {

namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw Error(message);
}

std::string got(int v) {
  return ", got " + std::to_string(v);
}

// The ranges; rules across options are in validate().
const IntOption<StereoParams> kStereoOptions[] = {
    {"minDisparity", "--min-disparity", "px", -2047, 2047, "smallest disparity searched",
     &StereoParams::minDisparity},
    {"numDisparities", "--num-disparities", "px", 16, 1024, "search range, a multiple of 16",
     &StereoParams::numDisparities},
    {"blockSize", "--block-size", "px", 3, 255, "odd side of the matching window",
     &StereoParams::blockSize},
    {"preFilterSize", "--pre-filter-size", "px", 5, 255,
     "odd window of the normalized-response prefilter", &StereoParams::preFilterSize},
    {"preFilterCap", "--pre-filter-cap", "", 1, 63, "prefilter clip", &StereoParams::preFilterCap},
    {"textureThreshold", "--texture-threshold", "", 0, 1 << 28,
     "least texture in the window; 0: off", &StereoParams::textureThreshold},
    {"uniquenessRatio", "--uniqueness-ratio", "%", 0, 1000,
     "margin by which the winner beats the rest; 0: off", &StereoParams::uniquenessRatio},
    {"disp12MaxDiff", "--disp12-max-diff", "px", -1, 2047, "left-right check tolerance; -1: off",
     &StereoParams::disp12MaxDiff},
    {"speckleWindowSize", "--speckle-window-size", "px", 0, 1 << 28, "largest blob removed; 0: off",
     &StereoParams::speckleWindowSize},
    {"speckleRange", "--speckle-range", "1/16 px", 0, 2047 * kDisparityScale,
     "largest step between neighbours of one blob", &StereoParams::speckleRange},
    {"leftBand", "--left-band", "px", 0, 1024,
     "match the left columns the whole range misses over the disparities that fit there, "
     "where at least this many do; 0: off",
     &StereoParams::leftBand},
};

const IntOption<MedianParams> kMedianOptions[] = {
    {"kernelSize", "--median-size", "px", 0, 5, "hole-filling median: 0 (off), 3 or 5",
     &MedianParams::kernelSize},
    {"minValidToFill", "--median-min-valid", "", 0, 25,
     "valid neighbours needed to fill a hole; 0: more than half the window",
     &MedianParams::minValidToFill},
};

}  // namespace

std::span<const IntOption<StereoParams>> stereoOptions() {
  return kStereoOptions;
}

std::span<const IntOption<MedianParams>> medianOptions() {
  return kMedianOptions;
}

StereoParams stereoBMDefaults(int numDisparities, int blockSize) {
  StereoParams p;
  p.minDisparity = 0;
  p.numDisparities = numDisparities > 0 ? numDisparities : 64;
  p.blockSize = blockSize;
  p.preFilterType = PreFilterType::XSobel;
  p.preFilterSize = 9;
  p.preFilterCap = 31;
  p.textureThreshold = 10;
  p.uniquenessRatio = 15;
  p.speckleWindowSize = 0;
  p.speckleRange = 0;
  p.disp12MaxDiff = -1;
  return p;
}

void validate(const StereoParams& p) {
  require(p.blockSize % 2 == 1, "blockSize must be odd (3..255)" + got(p.blockSize));
  require(p.preFilterSize % 2 == 1, "preFilterSize must be odd (5..255)" + got(p.preFilterSize));
  for (const IntOption<StereoParams>& o : kStereoOptions)
    checkRange(o, p);
  require(p.numDisparities % 16 == 0,
          "numDisparities must be a positive multiple of 16" + got(p.numDisparities));
  require(p.leftBand <= p.numDisparities,
          "leftBand must be within 0..numDisparities (0 = off)" + got(p.leftBand));
  // Every output, the invalid marker included, must fit int16 in 1/16 px.
  const long lowest = (static_cast<long>(p.minDisparity) - 1) * kDisparityScale;
  const long highest = (static_cast<long>(p.minDisparity) + p.numDisparities) * kDisparityScale;
  require(lowest >= std::numeric_limits<std::int16_t>::min() &&
              highest <= std::numeric_limits<std::int16_t>::max(),
          "minDisparity + numDisparities must stay within -2047..2047 pixels so that 16 * "
          "disparity fits int16" +
              got(p.minDisparity));
  require(p.preFilterType == PreFilterType::None || p.preFilterType == PreFilterType::XSobel ||
              p.preFilterType == PreFilterType::NormalizedResponse,
          "preFilterType must be NormalizedResponse (0), XSobel (1) or None (2)" +
              got(static_cast<int>(p.preFilterType)));
}

const char* toString(PreFilterType t) {
  switch (t) {
    case PreFilterType::NormalizedResponse:
      return "normalized";
    case PreFilterType::XSobel:
      return "xsobel";
    case PreFilterType::None:
      return "none";
  }
  return "invalid";
}

PreFilterType parsePreFilterType(const std::string& s) {
  if (s == "normalized") return PreFilterType::NormalizedResponse;
  if (s == "xsobel") return PreFilterType::XSobel;
  if (s == "none") return PreFilterType::None;
  throw Error("unknown pre-filter type '" + s + "': use normalized, xsobel or none");
}

int effectiveMinValid(const MedianParams& m) {
  if (m.minValidToFill > 0) return m.minValidToFill;
  return m.kernelSize * m.kernelSize / 2 + 1;
}

void validate(const MedianParams& m) {
  require(m.kernelSize == 0 || m.kernelSize == 3 || m.kernelSize == 5,
          "median kernel size (kernelSize) must be 0 (off), 3 or 5" + got(m.kernelSize));
  for (const IntOption<MedianParams>& o : kMedianOptions)
    checkRange(o, m);
  require(m.minValidToFill <= m.kernelSize * m.kernelSize,
          "median minValidToFill must be within 0..kernelSize^2 (0 = more than half)" +
              got(m.minValidToFill));
}

}  // namespace horopter
