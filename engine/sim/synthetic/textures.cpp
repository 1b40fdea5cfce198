// Loads the scene's textures once; see textures.hpp.
#include "synthetic/textures.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iostream>

#include "io/image_files.hpp"
#include "synthetic/rng.hpp"

namespace horopter::synth {

Texture::Texture(const cv::Mat& bgr8) {
  cv::Mat level;
  bgr8.convertTo(level, CV_32FC3);
  levels_.push_back(level);
  while (levels_.size() < 8 && level.cols >= 16 && level.rows >= 16) {
    cv::Mat down;
    cv::pyrDown(level, down);
    levels_.push_back(down);
    level = down;
  }
  for (std::size_t i = 0; i < levels_.size(); ++i) {
    const cv::Mat& l = levels_[i];
    LevelView view{l.ptr<float>(0), l.step1(), l.cols, l.rows};
    view.scale = std::ldexp(1.0, -static_cast<int>(i));
    const auto powerOfTwo = [](int n) { return n > 0 && (n & (n - 1)) == 0; };
    view.wrapByMask = powerOfTwo(l.cols) && powerOfTwo(l.rows);
    view.wMask = l.cols - 1;
    view.hMask = l.rows - 1;
    views_.push_back(view);
  }
  lastLevel_ = static_cast<int>(views_.size()) - 1;
  lastLevelLod_ = lastLevel_;
}

namespace {

const std::string kSkimage = "/usr/lib/python3/dist-packages/skimage/data/";
const std::string kOpencvDoc = "/usr/share/doc/opencv-doc/examples/data/";

// Multi-octave value noise in [0, 1], periodic over the image, from `seed`.
cv::Mat valueNoise(int size, std::uint64_t seed, int baseCells) {
  cv::Mat sum(size, size, CV_32F, cv::Scalar(0));
  SplitMix64 rng(seed);
  float amplitude = 1, total = 0;
  for (int cells = baseCells; cells <= size / 2; cells *= 2) {
    cv::Mat grid(cells, cells, CV_32F);
    for (int i = 0; i < cells * cells; ++i)
      grid.at<float>(i) = static_cast<float>(rng.uniform(0, 1));
    // Tile 3x3 before resizing so the octave stays periodic.
    cv::Mat tiled, up;
    cv::repeat(grid, 3, 3, tiled);
    cv::resize(tiled, up, cv::Size(3 * size, 3 * size), 0, 0, cv::INTER_CUBIC);
    sum += amplitude * up(cv::Rect(size, size, size, size));
    total += amplitude;
    amplitude *= 0.6f;
  }
  return sum / total;
}

// A grey noise pattern coloured by `tint` (BGR), contrast `contrast`.
cv::Mat tintedNoise(int size, std::uint64_t seed, int baseCells, cv::Vec3f tint, float contrast) {
  const cv::Mat n = valueNoise(size, seed, baseCells);
  cv::Mat out(size, size, CV_8UC3);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const float k = 1.0f + contrast * (2.0f * n.at<float>(y, x) - 1.0f);
      out.at<cv::Vec3b>(y, x) =
          cv::Vec3b(cv::saturate_cast<uchar>(tint[0] * k), cv::saturate_cast<uchar>(tint[1] * k),
                    cv::saturate_cast<uchar>(tint[2] * k));
    }
  return out;
}

// Wood grain: rings distorted by noise, in light skin-like tones (a
// distractor for skin detectors by design; no wood photograph ships in the
// packages we use).
cv::Mat woodTexture(int size) {
  const cv::Mat n = valueNoise(size, 77, 4);
  cv::Mat out(size, size, CV_8UC3);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double rings = std::sin(2 * CV_PI * (6.0 * y / size + 3.0 * n.at<float>(y, x)));
      const float k = static_cast<float>(0.82 + 0.18 * rings) *
                      (0.9f + 0.2f * n.at<float>((y * 7) % size, (x * 3) % size));
      out.at<cv::Vec3b>(y, x) =
          cv::Vec3b(cv::saturate_cast<uchar>(120 * k), cv::saturate_cast<uchar>(160 * k),
                    cv::saturate_cast<uchar>(205 * k));
    }
  return out;
}

// A grey image tinted towards `tint` (BGR, 128 = unchanged).
cv::Mat tint(const cv::Mat& bgr, cv::Vec3f t) {
  cv::Mat out;
  cv::multiply(bgr, cv::Scalar(t[0] / 128.0, t[1] / 128.0, t[2] / 128.0), out);
  return out;
}

struct Spec {
  TextureId id;
  const char* name;
  std::string path;  // empty: procedural by design
};

struct Library {
  std::array<Texture, static_cast<std::size_t>(TextureId::Count)> textures;
  std::vector<TextureSource> sources;
};

// The face crop of astronaut.png (Eileen Collins, public domain, NASA): the
// Haar face box is (177, 67, 93, 93); the crop adds forehead, hair and sides
// in the proportions of the head ellipsoid (0.17 m x 0.23 m).
const cv::Rect kAstronautHead(166, 27, 115, 156);

cv::Mat procedural(TextureId id) {
  switch (id) {
    case TextureId::Brick:
      return tintedNoise(256, 11, 8, {90, 100, 150}, 0.35f);
    case TextureId::Gravel:
      return tintedNoise(256, 12, 16, {110, 120, 125}, 0.45f);
    case TextureId::Grass:
      return tintedNoise(256, 13, 16, {60, 140, 70}, 0.4f);
    case TextureId::Face:
    case TextureId::FaceOther: {
      // A plain skin oval with eyes and mouth: looks like a face, but do not
      // expect a Haar cascade to fire on it.
      cv::Mat f = tintedNoise(128, 14, 8, {120, 150, 200}, 0.1f);
      cv::resize(f, f, kAstronautHead.size());
      const int w = f.cols, h = f.rows;
      cv::rectangle(f, cv::Rect(0, 0, w, h / 5), cv::Scalar(30, 40, 60), cv::FILLED);
      cv::circle(f, {w * 35 / 100, h * 45 / 100}, w / 14, cv::Scalar(40, 30, 30), cv::FILLED);
      cv::circle(f, {w * 65 / 100, h * 45 / 100}, w / 14, cv::Scalar(40, 30, 30), cv::FILLED);
      cv::ellipse(f, {w / 2, h * 72 / 100}, {w / 7, h / 30}, 0, 0, 360, cv::Scalar(60, 60, 150),
                  cv::FILLED);
      return f;
    }
    case TextureId::PosterA:
      return tintedNoise(256, 15, 4, {80, 140, 210}, 0.5f);
    case TextureId::PosterB:
      return tintedNoise(256, 16, 4, {200, 120, 60}, 0.5f);
    case TextureId::PosterC:
      return tintedNoise(256, 17, 4, {70, 180, 180}, 0.5f);
    case TextureId::PosterD:
      return tintedNoise(256, 18, 4, {150, 150, 150}, 0.5f);
    default:
      return tintedNoise(256, 19, 16, {128, 128, 128}, 0.3f);
  }
}

// The loaded image prepared for its use (tints, crops), or empty.
cv::Mat prepare(TextureId id, const cv::Mat& raw) {
  switch (id) {
    case TextureId::Brick:
      return tint(raw, {100, 115, 160});
    case TextureId::Gravel:
      return tint(raw, {120, 125, 130});
    case TextureId::Grass:
      return tint(raw, {80, 150, 90});
    case TextureId::Face:
    case TextureId::FaceOther: {
      if (raw.cols < kAstronautHead.br().x || raw.rows < kAstronautHead.br().y) return {};
      cv::Mat crop = raw(kAstronautHead).clone();
      if (id == TextureId::FaceOther) cv::flip(crop, crop, 1);
      return crop;
    }
    default:
      return raw;
  }
}

Library load() {
  const std::vector<Spec> specs = {
      {TextureId::Brick, "brick", kSkimage + "brick.png"},
      {TextureId::Gravel, "gravel", kSkimage + "gravel.png"},
      {TextureId::Grass, "grass", kSkimage + "grass.png"},
      {TextureId::Wood, "wood (procedural)", ""},
      {TextureId::Noise, "noise (procedural)", ""},
      {TextureId::Face, "astronaut", kSkimage + "astronaut.png"},
      {TextureId::FaceOther, "astronaut (mirrored)", kSkimage + "astronaut.png"},
      {TextureId::PosterA, "orange", kOpencvDoc + "orange.jpg"},
      {TextureId::PosterB, "messi5", kOpencvDoc + "messi5.jpg"},
      {TextureId::PosterC, "fruits", kOpencvDoc + "fruits.jpg"},
      {TextureId::PosterD, "chelsea", kSkimage + "chelsea.png"},
  };
  Library lib;
  std::vector<std::string> missing;
  for (const Spec& s : specs) {
    cv::Mat img;
    if (s.path.empty()) {
      img = s.id == TextureId::Wood ? woodTexture(256)
                                    : tintedNoise(256, 20, 32, {128, 128, 128}, 0.25f);
    } else {
      // Not cv::imread: astronaut.png and chelsea.png carry a faulty sRGB
      // profile, which libpng reports on every run.
      const cv::Mat raw = readImage(s.path, cv::IMREAD_COLOR);
      if (!raw.empty()) img = prepare(s.id, raw);
      lib.sources.push_back({s.name, s.path, !img.empty()});
      if (img.empty()) {
        missing.push_back(s.path);
        img = procedural(s.id);
      }
    }
    lib.textures[static_cast<std::size_t>(s.id)] = Texture(img);
  }
  if (!missing.empty()) {
    std::cerr << "horopter synthetic scene: warning: " << missing.size()
              << " texture file(s) not found, using procedural textures instead:";
    for (const std::string& m : missing)
      std::cerr << ' ' << m;
    std::cerr << " (install python3-skimage and opencv-doc: scripts/setup.sh)\n";
  }
  return lib;
}

const Library& library() {
  static const Library lib = load();  // thread-safe, once per process
  return lib;
}

}  // namespace

const Texture& texture(TextureId id) {
  return library().textures[static_cast<std::size_t>(id)];
}

std::vector<TextureSource> loadedTextureSources() {
  return library().sources;
}

}  // namespace horopter::synth
