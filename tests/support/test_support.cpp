#include "test_support.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace horopter::test {

std::uint64_t Rng::next() {
  std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

int Rng::uniform(int lo, int hi) {
  const auto span = static_cast<std::uint64_t>(static_cast<std::int64_t>(hi) - lo + 1);
  return static_cast<int>(lo + static_cast<std::int64_t>(next() % span));
}

namespace {

std::uint8_t canaryByte(std::size_t i) {
  return static_cast<std::uint8_t>(0xA5 ^ (i * 37) ^ (i >> 7));
}

}  // namespace

TestImage::TestImage(int width, int height, PixelType type, const Layout& layout)
    : width_(width), height_(height), type_(type), layout_(layout) {
  const auto bpp = static_cast<std::ptrdiff_t>(pixelBytes(type));
  // Keep 16-bit rows 2-byte aligned (an odd stride would be undefined
  // behaviour for any int16 access, not a property of the kernels).
  const std::ptrdiff_t canary = (layout.canaryBytes + bpp - 1) / bpp * bpp;
  stride_ = (layout.originX + width) * bpp + canary;
  const std::size_t rows = static_cast<std::size_t>(layout.rowsAbove + height + layout.rowsBelow);
  bytes_.resize(rows * static_cast<std::size_t>(stride_));
  for (std::size_t i = 0; i < bytes_.size(); ++i)
    bytes_[i] = canaryByte(i);
  offset_ = static_cast<std::size_t>(layout.rowsAbove * stride_ + layout.originX * bpp);
  fillBytes(0);
}

void TestImage::fillBytes(std::uint8_t value) {
  const std::size_t rowBytes = static_cast<std::size_t>(width_) * pixelBytes(type_);
  for (int y = 0; y < height_; ++y)
    std::memset(row<std::uint8_t>(y), value, rowBytes);
}

void TestImage::copyFrom(const ConstImageView& src) {
  if (src.width != width_ || src.height != height_ || src.type != type_)
    throw std::runtime_error("TestImage::copyFrom: size or type differs");
  const std::size_t rowBytes = static_cast<std::size_t>(width_) * pixelBytes(type_);
  for (int y = 0; y < height_; ++y)
    std::memcpy(row<std::uint8_t>(y), src.row<std::uint8_t>(y), rowBytes);
}

TestImage TestImage::clone(const Layout& layout) const {
  TestImage out(width_, height_, type_, layout);
  out.copyFrom(view());
  return out;
}

TestImage copyOf(const ConstImageView& src, const Layout& layout) {
  TestImage out(src.width, src.height, src.type, layout);
  out.copyFrom(src);
  return out;
}

::testing::AssertionResult TestImage::canariesIntact() const {
  const std::size_t rowBytes = static_cast<std::size_t>(width_) * pixelBytes(type_);
  std::size_t bad = 0, first = 0;
  for (std::size_t i = 0; i < bytes_.size(); ++i) {
    // Inside the pixels?
    if (i >= offset_) {
      const std::size_t rel = i - offset_;
      const std::size_t y = rel / static_cast<std::size_t>(stride_);
      const std::size_t x = rel % static_cast<std::size_t>(stride_);
      if (y < static_cast<std::size_t>(height_) && x < rowBytes) continue;
    }
    if (bytes_[i] != canaryByte(i)) {
      if (bad == 0) first = i;
      ++bad;
    }
  }
  if (bad == 0) return ::testing::AssertionSuccess();
  const auto firstRel = static_cast<std::ptrdiff_t>(first) - static_cast<std::ptrdiff_t>(offset_);
  return ::testing::AssertionFailure()
         << bad << " canary byte(s) outside the " << width_ << "x" << height_ << " "
         << pixelTypeName(type_) << " view (layout " << layout_.name << ", stride " << stride_
         << ") were overwritten; the first at byte " << firstRel << " from the view's origin (row "
         << (firstRel >= 0 ? firstRel / stride_ : -1) << ", byte "
         << (firstRel >= 0 ? firstRel % stride_ : firstRel) << " of that row)";
}

namespace {

std::string pixelValue(const ConstImageView& v, int x, int y) {
  switch (v.type) {
    case PixelType::U8C1:
      return std::to_string(v.row<std::uint8_t>(y)[x]);
    case PixelType::U8C3: {
      // (an ostringstream: GCC 12 gives a false -Wrestrict on chains of string +)
      const auto* p = v.row<std::uint8_t>(y) + 3 * x;
      std::ostringstream o;
      o << "(" << int(p[0]) << "," << int(p[1]) << "," << int(p[2]) << ")";
      return o.str();
    }
    case PixelType::S16C1:
      return std::to_string(v.row<std::int16_t>(y)[x]);
  }
  return "?";
}

}  // namespace

::testing::AssertionResult sameImage(const ConstImageView& expected, const ConstImageView& actual) {
  if (expected.type != actual.type)
    return ::testing::AssertionFailure() << "pixel type " << pixelTypeName(actual.type)
                                         << ", expected " << pixelTypeName(expected.type);
  if (expected.width != actual.width || expected.height != actual.height)
    return ::testing::AssertionFailure()
           << "size " << actual.width << "x" << actual.height << ", expected " << expected.width
           << "x" << expected.height;
  const std::size_t bpp = pixelBytes(expected.type);
  long differing = 0;
  std::ostringstream firsts;
  for (int y = 0; y < expected.height; ++y) {
    const auto* e = expected.row<std::uint8_t>(y);
    const auto* a = actual.row<std::uint8_t>(y);
    for (int x = 0; x < expected.width; ++x) {
      if (std::memcmp(e + x * bpp, a + x * bpp, bpp) == 0) continue;
      if (differing < 8)
        firsts << "\n  (" << x << ", " << y << "): expected " << pixelValue(expected, x, y)
               << ", got " << pixelValue(actual, x, y);
      ++differing;
    }
  }
  if (differing == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << differing << " of " << expected.width * expected.height
                                       << " pixels differ; first ones:" << firsts.str();
}

std::uint64_t fnv1a64(const ConstImageView& view) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  const std::size_t rowBytes = static_cast<std::size_t>(view.width) * pixelBytes(view.type);
  for (int y = 0; y < view.height; ++y) {
    const auto* p = view.row<std::uint8_t>(y);
    for (std::size_t i = 0; i < rowBytes; ++i) {
      h ^= p[i];
      h *= 0x100000001b3ull;
    }
  }
  return h;
}

std::string hex64(std::uint64_t value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%016llx", static_cast<unsigned long long>(value));
  return buf;
}

void fillRandom(const ImageView& view, Rng& rng, int lo, int hi) {
  const int channels = view.type == PixelType::U8C3 ? 3 : 1;
  for (int y = 0; y < view.height; ++y) {
    for (int x = 0; x < view.width * channels; ++x) {
      if (view.type == PixelType::S16C1) {
        view.row<std::int16_t>(y)[x] = static_cast<std::int16_t>(rng.uniform(lo, hi));
      } else {
        view.row<std::uint8_t>(y)[x] = static_cast<std::uint8_t>(rng.uniform(lo, hi));
      }
    }
  }
}

TestImage randomImage(int width, int height, PixelType type, std::uint64_t seed, int lo, int hi,
                      const Layout& layout) {
  TestImage image(width, height, type, layout);
  Rng rng(seed);
  fillRandom(image.view(), rng, lo, hi);
  return image;
}

WideTexture makeTexture(int width, int height, int margin, Texture kind, std::uint64_t seed) {
  WideTexture t;
  t.width = width;
  t.height = height;
  t.margin = margin;
  const int full = width + 2 * margin;
  t.pixels.resize(static_cast<std::size_t>(full) * height);
  Rng rng(seed);
  for (int y = 0; y < height; ++y) {
    std::uint8_t* row = &t.pixels[static_cast<std::size_t>(y) * full];
    int value = rng.uniform(kWalkStep, 255 - kWalkStep);
    for (int i = 0; i < full; ++i) {
      switch (kind) {
        case Texture::Uniform:
          row[i] = static_cast<std::uint8_t>(rng.uniform(0, 255));
          break;
        case Texture::LowEntropy:
          row[i] = static_cast<std::uint8_t>(rng.uniform(0, 3));
          break;
        case Texture::RandomWalk: {
          // Every horizontal step is exactly +-kWalkStep (turning back at the
          // ends of 0..255), so the SAD of a shifted copy rises by the same
          // amount at shift - 1 and shift + 1.
          const int step = rng.chance(50) ? kWalkStep : -kWalkStep;
          if (value + step < 0 || value + step > 255) {
            value -= step;
          } else {
            value += step;
          }
          row[i] = static_cast<std::uint8_t>(value);
          break;
        }
      }
    }
  }
  return t;
}

StereoPair shiftedPair(int width, int height, int shift, Texture kind, std::uint64_t seed,
                       int noise) {
  const int margin = std::abs(shift) + 1;
  const WideTexture tex = makeTexture(width, height, margin, kind, seed);
  StereoPair pair{TestImage(width, height, PixelType::U8C1),
                  TestImage(width, height, PixelType::U8C1)};
  Rng rng(seed ^ 0x5eedull);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      pair.left.at<std::uint8_t>(x, y) = tex(x, y);
      int r = tex(x + shift, y);
      if (noise > 0) r = std::clamp(r + rng.uniform(-noise, noise), 0, 255);
      pair.right.at<std::uint8_t>(x, y) = static_cast<std::uint8_t>(r);
    }
  }
  return pair;
}

StereoPair stepScenePair(int width, int height, const StepScene& s, std::uint64_t seed) {
  const int margin = std::max(std::abs(s.nearD), std::abs(s.farD)) + 1;
  const WideTexture far = makeTexture(width, height, margin, Texture::Uniform, seed);
  const WideTexture near = makeTexture(width, height, margin, Texture::Uniform, seed + 1);
  StereoPair pair{TestImage(width, height, PixelType::U8C1),
                  TestImage(width, height, PixelType::U8C1)};
  for (int y = 0; y < height; ++y) {
    const bool squareRow = y >= s.y0 && y < s.y1;
    for (int x = 0; x < width; ++x) {
      // Left view: the square's surface texture is attached to its left columns.
      const bool inSquareLeft = squareRow && x >= s.x0 && x < s.x1;
      pair.left.at<std::uint8_t>(x, y) = inSquareLeft ? near(x, y) : far(x, y);
      // Right view: the square moved left by nearD, the background by farD.
      const int xl = x + s.nearD;  // left column of the square point seen here
      const bool inSquareRight = squareRow && xl >= s.x0 && xl < s.x1;
      pair.right.at<std::uint8_t>(x, y) = inSquareRight ? near(xl, y) : far(x + s.farD, y);
    }
  }
  return pair;
}

TestImage randomDisparityMap(int width, int height, const StereoParams& params, std::uint64_t seed,
                             int invalidPercent, const Layout& layout) {
  TestImage map(width, height, PixelType::S16C1, layout);
  Rng rng(seed);
  const int lo = params.minDisparity * kDisparityScale;
  const int hi = (params.minDisparity + params.numDisparities - 1) * kDisparityScale;
  const std::int16_t invalid = invalidDisparity(params);
  // Blobs: rectangles of random size painted over each other, each with a
  // base value; then per-pixel steps of 0..40 (some joined, some not at the
  // default speckleRange of 32), lone speckles and invalid pixels.
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      map.at<std::int16_t>(x, y) = static_cast<std::int16_t>(lo);
  const int blobs = 4 + width * height / 40;
  for (int b = 0; b < blobs; ++b) {
    const int w = rng.uniform(1, std::max(1, width / 3));
    const int h = rng.uniform(1, std::max(1, height / 3));
    const int x0 = rng.uniform(0, width - 1);
    const int y0 = rng.uniform(0, height - 1);
    const int value = rng.uniform(lo, hi);
    for (int y = y0; y < std::min(height, y0 + h); ++y)
      for (int x = x0; x < std::min(width, x0 + w); ++x)
        map.at<std::int16_t>(x, y) = static_cast<std::int16_t>(value);
  }
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      auto& v = map.at<std::int16_t>(x, y);
      if (rng.chance(invalidPercent)) {
        v = invalid;
      } else if (rng.chance(3)) {
        v = static_cast<std::int16_t>(rng.uniform(lo, hi));
      } else if (rng.chance(30)) {
        v = static_cast<std::int16_t>(std::clamp(v + rng.uniform(-40, 40), lo, hi));
      }
    }
  }
  return map;
}

std::string sharedDataDir() {
  return HOROPTER_SHARED_DATA_DIR;
}

std::string opencvDataDir() {
  return HOROPTER_OPENCV_DATA_DIR;
}

bool isFile(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

}  // namespace horopter::test
