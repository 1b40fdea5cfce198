// Parameters of the stereo front end, with the names cv::StereoBM users know.
//
// Disparity maps are int16 in 1/16 pixel (kDisparityScale), as OpenCV's: divide
// by 16 to get pixels. An invalid pixel holds invalidDisparity(params), which is
// (minDisparity - 1) * 16, as OpenCV's.
#pragma once

#include "horopter/core/export.hpp"

#include <cstdint>
#include <span>
#include <string>

#include "horopter/core/option_table.hpp"

namespace horopter {

constexpr int kDisparityShift = 4;
constexpr int kDisparityScale = 1 << kDisparityShift;  // 16 steps per pixel

// The values of the two cv::StereoBM types are OpenCV's (PREFILTER_NORMALIZED_RESPONSE = 0,
// PREFILTER_XSOBEL = 1); None is Horopter's own.
enum class PreFilterType {
  // Each pixel's neighbourhood mean subtracted, clipped (OpenCV's
  // PREFILTER_NORMALIZED_RESPONSE, cv::StereoBM's prefilterNorm); its window is preFilterSize.
  NormalizedResponse = 0,
  XSobel = 1,  // the clipped horizontal Sobel response (OpenCV's PREFILTER_XSOBEL)
  None = 2     // match raw intensities
};

struct HOROPTER_API StereoParams {
  // Smallest disparity searched, in pixels. May be negative.
  int minDisparity = 0;
  // Size of the search range in pixels; a positive multiple of 16.
  int numDisparities = 64;
  // Side of the square matching window; odd, 3..255.
  int blockSize = 9;
  PreFilterType preFilterType = PreFilterType::XSobel;
  // Side of the normalized-response prefilter's averaging window; odd, 5..255
  // (used only by PreFilterType::NormalizedResponse; OpenCV's default 9).
  int preFilterSize = 9;
  // The prefilter's response is clipped to [-cap, cap]; 1..63.
  int preFilterCap = 31;
  // A pixel whose window sums less texture than this is invalid. 0 = off. The
  // texture is |prefiltered - cap| of the left view, as cv::StereoBM's: the
  // clipped |x-Sobel| with XSobel (and with None), the clipped |normalized
  // response| with NormalizedResponse.
  int textureThreshold = 10;
  // Percent margin by which the best cost must beat every other cost (except
  // its two neighbours). 0 = off.
  int uniquenessRatio = 15;
  // Largest allowed difference, in whole pixels, between the left disparity
  // and the right view's own winner. Negative = left-right check off.
  int disp12MaxDiff = 1;
  // Connected blobs of at most this many pixels are invalidated. 0 = off.
  int speckleWindowSize = 100;
  // Largest step between 4-neighbours of one blob, in the map's 1/16-pixel
  // units (as cv::StereoBM, which does not scale it; StereoSGBM does).
  int speckleRange = 32;
  // The left band: the left view's first numDisparities + blockSize / 2
  // columns, which no disparity of the whole range can match (the window
  // would leave the right image), are matched over the part of the range
  // that fits, where that is at least this many disparities. 0 = off (as
  // cv::StereoBM, which leaves them invalid). Horopter's own; see
  // kernels/sad/sad_scalar.cpp.
  int leftBand = 0;
};

// The invalid marker: (minDisparity - 1) * 16.
inline std::int16_t invalidDisparity(const StereoParams& p) {
  return static_cast<std::int16_t>((p.minDisparity - 1) * kDisparityScale);
}

// cv::StereoBM::create(numDisparities, blockSize)'s settings, exactly as
// OpenCV 4's StereoBMParams sets them (the defaults of StereoBM, stated here
// once for C++, Python's horopter.StereoBM_create and the agreement test):
//   numDisparities: as given, 0 (or negative) meaning 64; blockSize: as given
//   (OpenCV's default 21); minDisparity 0; preFilterType XSobel (StereoBM's
//   default, PREFILTER_XSOBEL; NormalizedResponse is its other type);
//   preFilterSize 9; preFilterCap 31; textureThreshold 10; uniquenessRatio 15;
//   speckleWindowSize 0 and speckleRange 0 (speckle filter off);
//   disp12MaxDiff -1 (left-right check off).
// Horopter's own StereoParams{} differ (64 disparities, block 9, the
// left-right check at 1 px and the speckle filter at 100 px / 32 on): they
// are the real-time front end's tuning, not StereoBM's. Not validated here
// (as cv::StereoBM::create, which checks at compute time): validate() does.
HOROPTER_API StereoParams stereoBMDefaults(int numDisparities = 0, int blockSize = 21);

// Throws horopter::Error naming the first bad parameter and its allowed range.
HOROPTER_API void validate(const StereoParams& p);

// "normalized" / "xsobel" / "none"; parsing throws horopter::Error on anything else.
HOROPTER_API const char* toString(PreFilterType t);
HOROPTER_API PreFilterType parsePreFilterType(const std::string& s);

// Invalid-aware median filter that fills holes.
struct HOROPTER_API MedianParams {
  // 0 (off), 3 or 5.
  int kernelSize = 5;
  // An invalid pixel is filled when at least this many pixels of its window
  // are valid; 0 = the default, more than half the window (5 of 9, 13 of 25).
  int minValidToFill = 0;
};

// The fill threshold in effect (resolves the 0 default).
HOROPTER_API int effectiveMinValid(const MedianParams& m);
HOROPTER_API void validate(const MedianParams& m);

// Every integer option of StereoParams and MedianParams, declared once (unit,
// range, help, flag), in the order `--help` lists them; preFilterType
// (--pre-filter-type normalized|xsobel|none) is the one choice. validate() checks these
// ranges, then the rules across options (a multiple of 16, an odd window,
// disparities that fit int16, a fill count within the window).
HOROPTER_API std::span<const IntOption<StereoParams>> stereoOptions();
HOROPTER_API std::span<const IntOption<MedianParams>> medianOptions();

}  // namespace horopter
