// The built-in synthetic stereo scene: rectified stereo pairs of a cluttered,
// textured room with two people, rendered from a virtual verging stereo head
// whose pose can be commanded every frame, with exact ground truth.
//
// Frames (all in metres, radians, pixels):
//  - world: x to the right, y DOWN, z forward (away from the robot); the rig's
//    cyclopean point is the origin, the floor is the plane y = +floorY.
//  - rig (the rectified cyclopean frame): origin midway between the camera
//    centres, x right, y down, z along the rectified optical axes; it is the
//    world frame turned by pan (about the vertical axis, positive turns the
//    view to the right) then tilt (positive looks down). The left camera
//    centre is (-B/2, 0, 0), the right one (+B/2, 0, 0).
// Both images are rendered already rectified (two parallel pinholes with the
// same focal length and principal point), so a point at rig depth Z has
// disparity f * B / Z pixels. Vergence only sets the fixation point (0, 0, D)
// with D = (B/2) / tan(vergence/2), and so the Vieth-Mueller circle through
// both camera centres and the fixation point in the rig's plane y = 0; the
// zone of interaction is the vertical (rig y) cylinder over that circle.
// Vergence 0 fixates at infinity: the circle becomes the half-plane z > 0.
//
// Textures come from Debian packages at run time (python3-skimage's data,
// opencv-doc's samples), never from the repository; a missing file gives one
// warning on stderr and a procedural texture instead.
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace horopter::synth {

struct HeadPose {
  double pan = 0;       // radians, positive: the rig looks to the right
  double tilt = 0;      // radians, positive: the rig looks down
  double vergence = 0;  // radians, total angle between the optical axes (0 = parallel)
};

// The vergence that fixates at `distanceM` straight ahead with baseline `baselineM`.
double vergenceForDistance(double baselineM, double distanceM);

// What the scene holds: everything, or only the room's six inner walls
// (planes with a known analytic depth, for tests).
enum class SceneContent { Full, EmptyRoom };

struct SceneOptions {
  int width = 640;
  int height = 480;
  std::uint64_t seed = 1;  // people's variability (speed, amplitude, height, handedness)
  double framesPerSecond = 30;
  double baselineM = 0.12;
  double focalPx = 0;      // 0: a 60 degree horizontal field of view
  bool distractor = true;  // the second person, outside the zone
  // The head pose before any commandHead: straight ahead, fixating at 2 m
  // (vergence 0.06 rad with the default baseline), so the main person, who
  // stops at 1.2-1.4 m, stands inside the zone.
  HeadPose initialHead{0.0, 0.0, 0.06};
  SceneContent content = SceneContent::Full;
  // Variations for the tracking trials (horopter eval-tracking); the defaults
  // leave the scene as it was.
  double lightingGain = 1;      // multiplies every rendered colour, (0, 4]
  double sensorNoiseSigma = 0;  // Gaussian noise per pixel and channel (grey levels), per view
  double personDistanceM = 0;   // the main person's station depth, metres (0: 1.2-1.4 m by seed)
  bool skinClutter = false;     // skin-coloured panels on the back wall, a rug and a poster
  // Per-pixel truth (FrameTruth's disparity, inside and occluded maps); off,
  // those maps stay empty and a frame costs less (the images, the people's
  // truth and the head pose are the same): for `horopter run`, which scores
  // nothing against them.
  bool pixelTruth = true;
  // Threads a frame is rendered on: 0, OpenCV's (cv::getNumThreads()); N,
  // at most N (1: the calling thread only, for a pipeline that already keeps
  // the other cores busy with other frames). The frames do not depend on it.
  int threads = 0;
};

enum class Movement { None, Circle, Pointing, WaveLeft, WaveRight, SagittalWave, ByeBye };
const char* movementName(Movement movement);

// One person's truth. 3-D positions in the rig frame (metres), 2-D positions
// in the left image (pixels), of the centres of the head and hands.
struct PersonTruth {
  int id = 0;               // 0: the main person, 1: the distractor
  bool visible = false;     // the head centre projects inside the left image, in front
  bool insideZone = false;  // the head centre lies inside the zone of interaction
  cv::Point2f head2d, leftHand2d, rightHand2d;
  cv::Point3f head3d, leftHand3d, rightHand3d;
  float faceWidthPx = 0;               // the face's width in the left image
  Movement movement = Movement::None;  // the movement being performed
};

struct FrameTruth {
  int index = 0;
  double timeS = 0;
  // Left view, CV_16SC1, 1/16 px: round(16 f B / Z) (halves away from zero)
  // for the rig depth Z of the visible surface; every pixel sees a surface.
  cv::Mat disparity;
  // CV_8UC1, 255 where the pixel's 3-D point lies strictly inside the zone.
  cv::Mat inside;
  // CV_8UC1, 255 where the left pixel's surface point is hidden in the right
  // view (occluded), so left(x, y) and right(x - d, y) show different things.
  cv::Mat occluded;
  std::vector<PersonTruth> people;
  HeadPose head;
  double fixationDistanceM = 0;  // infinity when vergence is 0
};

struct SyntheticFrame {
  cv::Mat left, right;  // CV_8UC3 BGR, rectified
  FrameTruth truth;
};

// Whether a texture came from its file or was replaced by a procedural one.
struct TextureSource {
  std::string name;  // "brick", "astronaut", ...
  std::string path;  // where it was looked for
  bool found = false;
};

// The textures the scene uses and where they came from (loads them once).
std::vector<TextureSource> textureSources();

class SceneRenderer;  // engine/synthetic: the ray caster and its caches

class SyntheticScene {
 public:
  // Throws horopter::Error for bad options (size, baseline, focal length, rate).
  explicit SyntheticScene(const SceneOptions& options);
  ~SyntheticScene();
  SyntheticScene(SyntheticScene&&) noexcept;
  SyntheticScene& operator=(SyntheticScene&&) noexcept;

  // Deterministic for (seed, frameIndex, head pose); frameIndex >= 0.
  SyntheticFrame render(int frameIndex);
  // The rig turns: later renders follow it (closed loop). Throws for a
  // non-finite pose, |pan| or |tilt| > 80 degrees, or vergence outside [0, 90).
  void commandHead(const HeadPose& pose);
  HeadPose head() const;

  // The rectified geometry of both views.
  double focalPx() const;
  double baselineM() const;
  double cx() const;
  double cy() const;
  const SceneOptions& options() const;

 private:
  SceneOptions options_;
  HeadPose head_;
  std::unique_ptr<SceneRenderer> renderer_;
};

}  // namespace horopter::synth
