#include "io/image_files.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "horopter/core/error.hpp"
#include "io/quiet_png.hpp"

namespace horopter {

namespace {

std::uint32_t bigEndian(std::span<const std::uint8_t> b, std::size_t at, int bytes) {
  std::uint32_t v = 0;
  for (int i = 0; i < bytes; ++i)
    v = (v << 8) | b[at + static_cast<std::size_t>(i)];
  return v;
}

std::uint32_t littleEndian32(std::span<const std::uint8_t> b, std::size_t at) {
  return std::uint32_t{b[at]} | (std::uint32_t{b[at + 1]} << 8) | (std::uint32_t{b[at + 2]} << 16) |
         (std::uint32_t{b[at + 3]} << 24);
}

bool startsWith(std::span<const std::uint8_t> b, const char* magic, std::size_t n) {
  return b.size() >= n && std::memcmp(b.data(), magic, n) == 0;
}

// Sides wider than int are clamped: they only need to compare as too large.
cv::Size sizeOf(std::uint64_t width, std::uint64_t height) {
  const auto clamp = [](std::uint64_t v) {
    return static_cast<int>(std::min<std::uint64_t>(v, std::uint64_t{1} << 30));
  };
  return {clamp(width), clamp(height)};
}

// PNG: the signature, then IHDR's length and type, then width and height.
std::optional<cv::Size> pngSize(std::span<const std::uint8_t> b) {
  if (b.size() < 24 || std::memcmp(b.data() + 12, "IHDR", 4) != 0) return std::nullopt;
  return sizeOf(bigEndian(b, 16, 4), bigEndian(b, 20, 4));
}

// JPEG: segments follow SOI; the first start-of-frame marker (C0-CF but C4
// DHT, C8 JPG and CC DAC) holds precision, height and width.
std::optional<cv::Size> jpegSize(std::span<const std::uint8_t> b) {
  std::size_t pos = 2;
  while (pos + 4 <= b.size()) {
    if (b[pos] != 0xFF) return std::nullopt;
    const std::uint8_t marker = b[pos + 1];
    if (marker == 0xFF) {  // fill byte
      ++pos;
      continue;
    }
    if (marker == 0xD8 || (marker >= 0xD0 && marker <= 0xD7) || marker == 0x01) {
      pos += 2;  // markers without a length
      continue;
    }
    const std::size_t length = bigEndian(b, pos + 2, 2);
    const bool startOfFrame =
        marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (startOfFrame) {
      if (pos + 9 > b.size()) return std::nullopt;
      return sizeOf(bigEndian(b, pos + 7, 2), bigEndian(b, pos + 5, 2));
    }
    if (length < 2) return std::nullopt;
    pos += 2 + length;
  }
  return std::nullopt;
}

// BMP: BITMAPINFOHEADER's signed width and height (negative = top-down).
std::optional<cv::Size> bmpSize(std::span<const std::uint8_t> b) {
  if (b.size() < 26) return std::nullopt;
  const auto side = [](std::uint32_t v) {
    const auto s = static_cast<std::int64_t>(static_cast<std::int32_t>(v));
    return static_cast<std::uint64_t>(s < 0 ? -s : s);
  };
  return sizeOf(side(littleEndian32(b, 18)), side(littleEndian32(b, 22)));
}

// PNM: "P1".."P6", then width and height as decimal text, with '#' comments.
std::optional<cv::Size> pnmSize(std::span<const std::uint8_t> b) {
  std::size_t pos = 2;
  std::uint64_t sides[2] = {0, 0};
  for (std::uint64_t& side : sides) {
    while (pos < b.size() && (std::isspace(b[pos]) || b[pos] == '#')) {
      if (b[pos] == '#')
        while (pos < b.size() && b[pos] != '\n')
          ++pos;
      else
        ++pos;
    }
    if (pos >= b.size() || !std::isdigit(b[pos])) return std::nullopt;
    while (pos < b.size() && std::isdigit(b[pos]) && side < (std::uint64_t{1} << 40))
      side = side * 10 + (b[pos++] - '0');
  }
  return sizeOf(sides[0], sides[1]);
}

}  // namespace

std::optional<cv::Size> imageHeaderSize(std::span<const std::uint8_t> bytes) {
  if (startsWith(bytes, "\x89PNG\r\n\x1a\n", 8)) return pngSize(bytes);
  if (startsWith(bytes, "\xFF\xD8", 2)) return jpegSize(bytes);
  if (startsWith(bytes, "BM", 2)) return bmpSize(bytes);
  if (bytes.size() >= 2 && bytes[0] == 'P' && bytes[1] >= '1' && bytes[1] <= '6')
    return pnmSize(bytes);
  return std::nullopt;
}

cv::Mat readImage(const std::string& path, int flags) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
  if (const auto size = imageHeaderSize(bytes);
      size && (size->width > kMaxImageSide || size->height > kMaxImageSide))
    throw Error("image '" + path + "' is " + std::to_string(size->width) + "x" +
                std::to_string(size->height) + ": larger than the " +
                std::to_string(kMaxImageSide) + "-pixel side Horopter reads");
  // Anything but a PNG goes through cv::imread as before (a JPEG's EXIF
  // orientation included).
  if (!startsWith(bytes, "\x89PNG\r\n\x1a\n", 8)) return cv::imread(path, flags);
  try {
    return cv::imdecode(withoutIccpChunks(std::move(bytes)), flags);
  } catch (const cv::Exception&) {
    return {};
  }
}

}  // namespace horopter
