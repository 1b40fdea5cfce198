// The scene's textures: real photographs and material images from Debian
// packages (python3-skimage's data, opencv-doc's samples), loaded once per
// process at run time; a missing file is replaced by a procedural texture
// with one warning on stderr.
#pragma once

#include <opencv2/core.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <string>
#include <vector>

#include "horopter/sim/synthetic_scene.hpp"

namespace horopter::synth {

// An image with its mipmaps, BGR as floats in [0, 255]. Sampling is
// trilinear: a surface far away shows the blurred texture instead of aliasing
// noise, which would differ between the two views.
class Texture {
 public:
  Texture() = default;
  explicit Texture(const cv::Mat& bgr8);

  int width() const { return levels_.empty() ? 0 : levels_[0].cols; }
  int height() const { return levels_.empty() ? 0 : levels_[0].rows; }
#if defined(__SSE2__)
  using Texel = __m128;  // B, G, R, 0: the three channels in one register
#else
  using Texel = cv::Vec3f;
#endif
  // (u, v) in texels of the full-size image, the texture repeating;
  // `footprint`: texels covered by one pixel (chooses the mipmap level).
  cv::Vec3f sampleWrap(double u, double v, double footprint) const;
  // As sampleWrap, but outside the image the border texel repeats.
  cv::Vec3f sampleClamp(double u, double v, double footprint) const;
  // The same colours as a Texel (for the rasteriser's shading).
  Texel sampleWrapTexel(double u, double v, double footprint) const;
  Texel sampleClampTexel(double u, double v, double footprint) const;

 private:
  template <bool Wrap>
  Texel sampleLevel(int level, double u, double v) const;
  template <bool Wrap>
  Texel sample(double u, double v, double footprint) const;
  std::vector<cv::Mat> levels_;  // CV_32FC3, each half the previous
  // Each level's texels as sampleLevel reads them (no cv::Mat lookups per
  // sample); they point into levels_.
  // Decided once per level, not per sample: the level's scale 2^-level and,
  // when both sides are powers of two, the masks that wrap an index.
  struct LevelView {
    const float* data = nullptr;
    std::size_t rowFloats = 0;  // from a row to the next
    int w = 0, h = 0;
    double scale = 1;          // 2^-level, exact
    bool wrapByMask = false;   // w and h powers of two
    int wMask = 0, hMask = 0;  // w - 1, h - 1 when wrapByMask
  };
  std::vector<LevelView> views_;
  int lastLevel_ = -1;        // views_.size() - 1, not derived per sample
  double lastLevelLod_ = -1;  // the same, as sample compares it
};

enum class TextureId {
  Brick,      // walls
  Gravel,     // floor
  Grass,      // a rug / plant box
  Wood,       // furniture: procedural, skin-coloured on purpose
  Noise,      // fine neutral noise: ceiling, clothes, skin
  Face,       // the main person's face (a crop of a real photograph)
  FaceOther,  // the distractor's face (the same photograph, mirrored)
  PosterA,    // posters: real photographs, some skin-coloured or with faces
  PosterB,
  PosterC,
  PosterD,
  Count
};

const Texture& texture(TextureId id);
std::vector<TextureSource> loadedTextureSources();

}  // namespace horopter::synth

#include "synthetic/texture_sampling.hpp"  // IWYU pragma: export
