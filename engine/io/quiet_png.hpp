// Reading image files without libpng's colour-profile warning.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace horopter {

// `bytes` without the chunks named iCCP when they are a PNG file; any other
// bytes (not a PNG, a truncated chunk) come back unchanged. An iCCP chunk is
// an embedded ICC colour profile, which OpenCV does not apply: dropping it
// leaves every decoded pixel the same.
std::vector<std::uint8_t> withoutIccpChunks(std::vector<std::uint8_t> bytes);

// cv::imread(path, flags), but a PNG's iCCP chunk is dropped before decoding,
// so that libpng does not print "libpng warning: iCCP: known incorrect sRGB
// profile" for files that carry a faulty profile (scikit-image's astronaut
// and chelsea). Every other warning and error of the decoder still shows.
// Returns an empty Mat where cv::imread would (missing, unreadable or
// undecodable file).
cv::Mat imreadWithoutColourProfile(const std::string& path, int flags);

}  // namespace horopter
