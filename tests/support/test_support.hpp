// Shared helpers of the test suite: a portable random generator, guarded test
// images (padded strides, ROI origins, canary bytes), image comparison,
// FNV-1a hashing, scene generators and the paths of the real data.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "horopter/core/error.hpp"
#include "horopter/core/image.hpp"
#include "horopter/kernels/stereo_params.hpp"

namespace horopter::test {

// The message of the horopter::Error that fn throws, or "" when it throws none.
std::string errorOf(auto&& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// splitmix64: the same sequence on every platform, compiler and standard
// library (std::uniform_int_distribution is not), so that golden hashes of
// generated inputs are reproducible.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  // Uniform in [lo, hi] (both included).
  int uniform(int lo, int hi);
  // True with the given probability in percent.
  bool chance(int percent) { return uniform(0, 99) < percent; }

 private:
  std::uint64_t state_;
};

// Where a view lies inside its buffer. Every byte of the buffer outside the
// view's pixels holds a canary pattern that kernels must not touch.
struct Layout {
  const char* name = "tight";
  int originX = 0;      // pixels before the view in each buffer row (ROI origin x)
  int canaryBytes = 0;  // bytes after each row of the view (stride padding)
  int rowsAbove = 0;    // buffer rows before the view (ROI origin y)
  int rowsBelow = 0;    // buffer rows after the view
};

// The tight layout allocates exactly height * width * bytes: under
// AddressSanitizer any read or write past the last pixel is reported.
inline constexpr Layout kTight{"tight", 0, 0, 0, 0};
inline constexpr Layout kPadded{"padded", 0, 22, 0, 0};
inline constexpr Layout kRoi{"roi", 5, 18, 3, 2};
inline constexpr Layout kLayouts[] = {kTight, kPadded, kRoi};

class TestImage {
 public:
  TestImage() = default;
  TestImage(int width, int height, PixelType type, const Layout& layout = kTight);

  int width() const { return width_; }
  int height() const { return height_; }
  PixelType type() const { return type_; }
  std::ptrdiff_t strideBytes() const { return stride_; }
  const Layout& layout() const { return layout_; }

  ImageView view() { return {bytes_.data() + offset_, width_, height_, stride_, type_}; }
  ConstImageView view() const { return {bytes_.data() + offset_, width_, height_, stride_, type_}; }
  ConstImageView cview() const { return view(); }

  template <typename T>
  T* row(int y) {
    return view().row<T>(y);
  }
  template <typename T>
  const T* row(int y) const {
    return view().row<T>(y);
  }
  template <typename T>
  T& at(int x, int y) {
    return row<T>(y)[x];
  }
  template <typename T>
  const T& at(int x, int y) const {
    return row<T>(y)[x];
  }

  // Copies the pixels of `src` (same size and type).
  void copyFrom(const ConstImageView& src);
  // A copy of the pixels in another layout.
  TestImage clone(const Layout& layout = kTight) const;
  // Sets every pixel byte (not the canaries) to `value`.
  void fillBytes(std::uint8_t value);
  // Success when every byte outside the pixels still holds the canary pattern.
  ::testing::AssertionResult canariesIntact() const;

 private:
  std::vector<std::uint8_t> bytes_;
  std::size_t offset_ = 0;
  int width_ = 0;
  int height_ = 0;
  std::ptrdiff_t stride_ = 0;
  PixelType type_ = PixelType::U8C1;
  Layout layout_{};
};

// Makes a test image from an arbitrary view, in the given layout.
TestImage copyOf(const ConstImageView& src, const Layout& layout = kTight);

// Bit-for-bit comparison of the pixels (padding ignored); on failure, says how
// many pixels differ and where the first ones are, with both values.
::testing::AssertionResult sameImage(const ConstImageView& expected, const ConstImageView& actual);

// FNV-1a 64 over the pixel bytes, row by row, without the padding.
std::uint64_t fnv1a64(const ConstImageView& view);
std::string hex64(std::uint64_t value);

// Generators. Values are drawn with Rng, so they are the same everywhere.
void fillRandom(const ImageView& view, Rng& rng, int lo, int hi);
TestImage randomImage(int width, int height, PixelType type, std::uint64_t seed, int lo, int hi,
                      const Layout& layout = kTight);

enum class Texture {
  Uniform,     // independent uniform bytes 0..255
  RandomWalk,  // each row a walk with steps of exactly +-kWalkStep (symmetric SAD around a shift)
  LowEntropy,  // bytes 0..3: many equal costs (ties)
};
inline constexpr int kWalkStep = 9;
// A W x H texture sampled on columns [-margin, W + margin): texture(x, y) is at
// column x + margin.
struct WideTexture {
  int width = 0, height = 0, margin = 0;
  std::vector<std::uint8_t> pixels;
  std::uint8_t operator()(int x, int y) const {
    return pixels[static_cast<std::size_t>(y) * (width + 2 * margin) + (x + margin)];
  }
};
WideTexture makeTexture(int width, int height, int margin, Texture kind, std::uint64_t seed);

struct StereoPair {
  TestImage left, right;
};
// A fronto-parallel textured plane at disparity `shift` px: left(x, y) =
// texture(x, y) and right(x, y) = texture(x + shift, y), so the left pixel x
// matches the right pixel x - shift. `noise` adds uniform +-noise to the right
// image (clamped to 0..255).
StereoPair shiftedPair(int width, int height, int shift, Texture kind, std::uint64_t seed,
                       int noise = 0);

// A near square (disparity `nearD`) in front of a far background (`farD`),
// both with independent uniform textures. The square covers left columns
// [x0, x1) and rows [y0, y1). Left pixels x in [x0 - (nearD - farD), x0) of
// those rows see background that the square hides from the right camera.
struct StepScene {
  int x0, x1, y0, y1, nearD, farD;
};
StereoPair stepScenePair(int width, int height, const StepScene& scene, std::uint64_t seed);

// A disparity map (S16C1, 1/16 px) made of blobs of various sizes with
// values in the search range of `params`, small steps inside blobs, isolated
// speckles and `invalidPercent` invalid pixels.
TestImage randomDisparityMap(int width, int height, const StereoParams& params, std::uint64_t seed,
                             int invalidPercent, const Layout& layout = kTight);

// Real data. The folders are fixed at configure time (HOROPTER_SHARED_DATA_DIR,
// HOROPTER_OPENCV_DATA_DIR); tests read the files where they lie.
std::string sharedDataDir();
std::string opencvDataDir();
bool isFile(const std::string& path);

}  // namespace horopter::test

// Skips the current test, visibly, unless `path` is a file.
#define HOROPTER_REQUIRE_FILE(path)                                                         \
  do {                                                                                      \
    const std::string horopterRequiredPath_ = (path);                                       \
    if (!::horopter::test::isFile(horopterRequiredPath_))                                   \
      GTEST_SKIP() << "test data not found: " << horopterRequiredPath_                      \
                   << " (the real data lives in ../shared/data beside the repository, and " \
                      "opencv-doc's examples in /usr/share/doc/opencv-doc/examples/data)";  \
  } while (0)
