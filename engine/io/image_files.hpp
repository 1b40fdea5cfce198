// Reading image files with their size checked before anything is decoded.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include <opencv2/core.hpp>

namespace horopter {

// The largest image side Horopter reads, in pixels (the calibration's own
// limit too). A colour image this size already takes 768 MiB; OpenCV's own
// limit (2^30 pixels) would let a small file ask for 3 GiB before failing.
constexpr int kMaxImageSide = 16384;

// Width and height from the header of a PNG, JPEG, BMP or PNM (PGM, PPM,
// PBM) file, without decoding; nullopt for other formats or a header that
// is cut short.
std::optional<cv::Size> imageHeaderSize(std::span<const std::uint8_t> bytes);

// cv::imread(path, flags), with two differences:
// - a file whose header gives a side over kMaxImageSide throws
//   horopter::Error naming the path and its size, before any pixel buffer
//   is allocated;
// - a PNG's iCCP chunk is dropped before decoding (quiet_png.hpp), so
//   libpng does not warn about faulty colour profiles.
// Returns an empty Mat where cv::imread would (missing, unreadable or
// undecodable file).
cv::Mat readImage(const std::string& path, int flags);

}  // namespace horopter
