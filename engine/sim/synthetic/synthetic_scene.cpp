// SyntheticScene: options, head pose, caches of the static room per view;
// see include/horopter/sim/synthetic_scene.hpp.
#include "horopter/sim/synthetic_scene.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "horopter/core/error.hpp"
#include "synthetic/people.hpp"
#include "synthetic/rasteriser.hpp"
#include "synthetic/room.hpp"
#include "synthetic/scene_renderer.hpp"
#include "synthetic/truth.hpp"

namespace horopter::synth {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

void validate(const SceneOptions& o) {
  if (o.width < 16 || o.height < 16 || o.width > 8192 || o.height > 8192)
    throw Error("synthetic scene size must be between 16x16 and 8192x8192, got " +
                std::to_string(o.width) + "x" + std::to_string(o.height));
  if (!std::isfinite(o.baselineM) || !(o.baselineM > 0) || o.baselineM > 2)
    throw Error("synthetic scene baselineM must be in (0, 2] metres, got " + num(o.baselineM) +
                ": use e.g. 0.12");
  if (!std::isfinite(o.focalPx) || o.focalPx < 0)
    throw Error(
        "synthetic scene focalPx must be positive (or 0 for a 60 degree field of view), got " +
        num(o.focalPx));
  if (!std::isfinite(o.framesPerSecond) || !(o.framesPerSecond > 0))
    throw Error("synthetic scene framesPerSecond must be positive, got " + num(o.framesPerSecond));
  if (!std::isfinite(o.lightingGain) || !(o.lightingGain > 0) || o.lightingGain > 4)
    throw Error("synthetic scene lightingGain must be in (0, 4], got " + num(o.lightingGain));
  if (!std::isfinite(o.sensorNoiseSigma) || o.sensorNoiseSigma < 0 || o.sensorNoiseSigma > 64)
    throw Error("synthetic scene sensorNoiseSigma must be in [0, 64] grey levels, got " +
                num(o.sensorNoiseSigma));
  if (o.threads < 0 || o.threads > 256)
    throw Error("synthetic scene threads must be 0 (OpenCV's) or 1..256, got " +
                std::to_string(o.threads));
  if (!std::isfinite(o.personDistanceM) || o.personDistanceM < 0 ||
      (o.personDistanceM > 0 && (o.personDistanceM < 0.6 || o.personDistanceM > 4)))
    throw Error("synthetic scene personDistanceM must be 0 (by seed) or in [0.6, 4] m, got " +
                num(o.personDistanceM));
}

// Lighting gain, then sensor noise drawn from (seed, frame, eye): the same
// frame renders the same way whatever else was rendered before.
void sensorEffects(const SceneOptions& o, int frameIndex, int eye, cv::Mat& image) {
  if (o.lightingGain != 1) image.convertTo(image, -1, o.lightingGain);
  if (o.sensorNoiseSigma > 0) {
    cv::RNG rng(o.seed * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(frameIndex) * 2 +
                static_cast<std::uint64_t>(eye) + 1);
    cv::Mat noise(image.size(), CV_16SC3);
    rng.fill(noise, cv::RNG::NORMAL, 0, o.sensorNoiseSigma);
    cv::add(image, noise, image, cv::noArray(), CV_8UC3);
  }
}

void validate(const HeadPose& p) {
  const double limit = 80 * kPi / 180;
  if (!std::isfinite(p.pan) || std::abs(p.pan) > limit)
    throw Error("head pan must be finite and within +-80 degrees (1.396 rad), got " + num(p.pan) +
                " rad");
  if (!std::isfinite(p.tilt) || std::abs(p.tilt) > limit)
    throw Error("head tilt must be finite and within +-80 degrees (1.396 rad), got " + num(p.tilt) +
                " rad");
  if (!std::isfinite(p.vergence) || p.vergence < 0 || p.vergence >= kPi / 2)
    throw Error("head vergence must be in [0, pi/2) rad (0 = parallel axes), got " +
                num(p.vergence) + " rad");
}

}  // namespace

// ---- SceneRenderer --------------------------------------------------------

SceneRenderer::SceneRenderer(const SceneOptions& options)
    : options_(options),
      focal_(options.focalPx > 0 ? options.focalPx
                                 : 0.5 * options.width / std::tan(30 * kPi / 180)),
      cx_(0.5 * (options.width - 1)),
      cy_(0.5 * (options.height - 1)),
      room_(room::build(options.content == SceneContent::Full, options.skinClutter)),
      people_(options.content == SceneContent::Full
                  ? makePeople(options.seed, options.distractor, options.personDistanceM)
                  : std::vector<PersonParams>{}) {
  // The room for the initial pose now, as a camera opens before its first
  // frame: a run's first frame then costs what the others do.
  updateStatic(options.initialHead);
  if (options.pixelTruth) updateStaticTruth(options.initialHead);
}

Camera SceneRenderer::camera(const HeadPose& head, int eye) const {
  Camera c;
  c.rigToWorld = rotationY(head.pan) * rotationX(head.tilt);
  c.centre = c.rigToWorld.apply(Vec3{(eye == 0 ? -0.5 : 0.5) * options_.baselineM, 0, 0});
  c.f = focal_;
  c.cx = cx_;
  c.cy = cy_;
  c.width = options_.width;
  c.height = options_.height;
  return c;
}

void SceneRenderer::updateStatic(const HeadPose& head) {
  // The images depend on pan and tilt only; vergence moves the zone.
  if (staticValid_ && head.pan == staticPan_ && head.tilt == staticTilt_) return;
  for (int eye = 0; eye < 2; ++eye) {
    staticLayer_[eye].reset(options_.width, options_.height);
    synth::render(camera(head, eye), room_, staticLayer_[eye], nullptr, stripes());
  }
  staticPan_ = head.pan;
  staticTilt_ = head.tilt;
  staticValid_ = true;
  staticTruthValid_ = false;
  frameValid_ = false;
  double minDepth = 0;
  cv::minMaxLoc(staticLayer_[0].depth, &minDepth);
  maxStaticDisparityPx_ = focal_ * options_.baselineM / minDepth;
}

void SceneRenderer::updateStaticTruth(const HeadPose& head) {
  if (staticTruthValid_ && head.vergence == staticTruthVergence_) return;
  allocatePixelTruth(options_.width, options_.height, staticTruth_);
  pixelTruth(camera(head, 0), staticLayer_[0], staticLayer_[1], options_.baselineM,
             ZoneCircle(options_.baselineM, head.vergence),
             cv::Rect(0, 0, options_.width, options_.height), staticTruth_, stripes());
  staticTruthVergence_ = head.vergence;
  staticTruthValid_ = true;
}

SyntheticFrame SceneRenderer::render(int frameIndex, const HeadPose& head) {
  if (frameIndex < 0)
    throw Error("synthetic scene frame index must be >= 0, got " + std::to_string(frameIndex));
  updateStatic(head);
  if (options_.pixelTruth) updateStaticTruth(head);
  const double t = frameIndex / options_.framesPerSecond;

  std::vector<PersonPose> poses;
  std::vector<Primitive> prims;
  for (const PersonParams& p : people_) {
    poses.push_back(poseAt(p, t));
    addPrimitives(p, poses.back(), prims);
  }
  // Incremental when the head is where it was for the last frame (so are
  // the room's layers and truth) and the people are made of as many parts.
  const bool incremental = frameValid_ && head.pan == frameHead_.pan &&
                           head.tilt == frameHead_.tilt && head.vergence == frameHead_.vergence &&
                           prims.size() == framePrimitives_.size();
  frameValid_ = false;  // until the frame is complete (an exception leaves it so)
  const cv::Rect image(0, 0, options_.width, options_.height);
  cv::Rect drawn[2];  // a full frame: where the people were drawn
  for (int eye = 0; eye < 2; ++eye) {
    const Camera cam = camera(head, eye);
    Layer& layer = frame_[eye];
    if (incremental) {
      // Where a changed part was or is now: the room goes back there and
      // every part is drawn again, there only.
      RowIntervals& redraw = redraw_[eye];
      redraw.reset(options_.height);
      for (std::size_t i = 0; i < prims.size(); ++i)
        if (!sameSurface(prims[i], framePrimitives_[i])) {
          coverage(cam, prims[i], redraw);
          coverage(cam, framePrimitives_[i], redraw);
        }
      redraw.merge();
      for (int y = 0; y < options_.height; ++y)
        for (const Interval& in : redraw.row(y)) {
          const int n = in.x1 - in.x0;
          std::copy_n(staticLayer_[eye].colour.ptr<cv::Vec3b>(y) + in.x0, n,
                      layer.colour.ptr<cv::Vec3b>(y) + in.x0);
          std::copy_n(staticLayer_[eye].depth.ptr<double>(y) + in.x0, n,
                      layer.depth.ptr<double>(y) + in.x0);
        }
      synth::render(cam, prims, layer, &redraw, stripes());
    } else {
      staticLayer_[eye].colour.copyTo(layer.colour);
      staticLayer_[eye].depth.copyTo(layer.depth);
      if (!prims.empty()) drawn[eye] = synth::render(cam, prims, layer, nullptr, stripes());
    }
  }

  SyntheticFrame frame;
  frame.left = frame_[0].colour.clone();
  frame.right = frame_[1].colour.clone();
  FrameTruth& truth = frame.truth;
  truth.index = frameIndex;
  truth.timeS = t;
  truth.head = head;
  const ZoneCircle zone(options_.baselineM, head.vergence);
  truth.fixationDistanceM = zone.fixationDistance();
  const Camera left = camera(head, 0);
  // Only pixels the people may have changed are computed again: those drawn
  // in the left view, and those whose match in the right view (x - d, with
  // d at most the largest disparity in the left view) fell where the right
  // view was drawn. The rest comes from the room's truth (a full frame) or
  // from the last frame (an incremental one).
  if (!options_.pixelTruth) {
    // No per-pixel truth: the maps stay empty.
  } else if (incremental) {
    // Left pixels outside the redrawn ones keep their depth, so their
    // disparity is at most that of the nearest surface in the left view.
    double minDepth = 0;
    cv::minMaxLoc(frame_[0].depth, &minDepth);
    const int reach = static_cast<int>(std::ceil(focal_ * options_.baselineM / minDepth)) + 2;
    truthRows_.reset(options_.height);
    for (int y = 0; y < options_.height; ++y) {
      for (const Interval& in : redraw_[0].row(y))
        truthRows_.add(y, in.x0, in.x1);
      for (const Interval& in : redraw_[1].row(y))
        truthRows_.add(y, in.x0, std::min(options_.width, in.x1 + reach));
    }
    truthRows_.merge();
    pixelTruth(left, frame_[0], frame_[1], options_.baselineM, zone, truthRows_, frameTruth_,
               stripes());
  } else {
    staticTruth_.disparity.copyTo(frameTruth_.disparity);
    staticTruth_.inside.copyTo(frameTruth_.inside);
    staticTruth_.occluded.copyTo(frameTruth_.occluded);
    cv::Rect dirty = drawn[0];
    if (!drawn[1].empty()) {
      cv::Rect shifted = drawn[1];
      shifted.width += static_cast<int>(std::ceil(maxStaticDisparityPx_)) + 2;
      dirty = dirty.empty() ? shifted : (dirty | shifted);
    }
    pixelTruth(left, frame_[0], frame_[1], options_.baselineM, zone, dirty, frameTruth_, stripes());
  }
  if (options_.pixelTruth) {
    truth.disparity = frameTruth_.disparity.clone();
    truth.inside = frameTruth_.inside.clone();
    truth.occluded = frameTruth_.occluded.clone();
  }
  framePrimitives_ = std::move(prims);
  frameHead_ = head;
  frameValid_ = true;
  for (std::size_t i = 0; i < people_.size(); ++i)
    truth.people.push_back(
        personTruth(left, frame_[0], options_.baselineM, zone, people_[i].id, poses[i]));
  sensorEffects(options_, frameIndex, 0, frame.left);
  sensorEffects(options_, frameIndex, 1, frame.right);
  return frame;
}

// ---- public API -------------------------------------------------------------

double vergenceForDistance(double baselineM, double distanceM) {
  if (!(baselineM > 0) || !(distanceM > 0) || !std::isfinite(baselineM))
    throw Error("vergenceForDistance needs a positive baseline and distance, got " +
                num(baselineM) + " and " + num(distanceM));
  return 2 * std::atan(0.5 * baselineM / distanceM);
}

const char* movementName(Movement movement) {
  switch (movement) {
    case Movement::None:
      return "none";
    case Movement::Circle:
      return "circle";
    case Movement::Pointing:
      return "pointing";
    case Movement::WaveLeft:
      return "wave-left";
    case Movement::WaveRight:
      return "wave-right";
    case Movement::SagittalWave:
      return "sagittal-wave";
    case Movement::ByeBye:
      return "bye-bye";
  }
  return "unknown";
}

std::vector<TextureSource> textureSources() {
  return loadedTextureSources();
}

SyntheticScene::SyntheticScene(const SceneOptions& options) : options_(options) {
  validate(options_);
  validate(options_.initialHead);
  head_ = options_.initialHead;
  renderer_ = std::make_unique<SceneRenderer>(options_);
}

SyntheticScene::~SyntheticScene() = default;
SyntheticScene::SyntheticScene(SyntheticScene&&) noexcept = default;
SyntheticScene& SyntheticScene::operator=(SyntheticScene&&) noexcept = default;

SyntheticFrame SyntheticScene::render(int frameIndex) {
  return renderer_->render(frameIndex, head_);
}

void SyntheticScene::commandHead(const HeadPose& pose) {
  validate(pose);
  head_ = pose;
}

HeadPose SyntheticScene::head() const {
  return head_;
}
double SyntheticScene::focalPx() const {
  return renderer_->focalPx();
}
double SyntheticScene::baselineM() const {
  return options_.baselineM;
}
double SyntheticScene::cx() const {
  return renderer_->cx();
}
double SyntheticScene::cy() const {
  return renderer_->cy();
}
const SceneOptions& SyntheticScene::options() const {
  return options_;
}

}  // namespace horopter::synth
