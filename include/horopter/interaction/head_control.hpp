// Head control: pan and tilt that keep the godfather's face centred, sent to
// a horopter::hw::Head. Two formulas:
//  - Atan2 (default): the exact angles that put the 3-D head point (rig
//    frame, from the disparity) on the optical axis, given the pose the frame
//    was captured with: pan = atan2(x_w, z_w), tilt = atan2(y_w, hypot(x_w, z_w))
//    with w the point turned into the head's base frame.
//  - Paper: tan(dtheta) = u / (phi f) with phi = d * lambda, u the face's
//    offset from the principal point (px), f the focal length (px), d the
//    head's distance (m) and lambda an empirical constant (1/m); phi = 1 gives
//    the pinhole angle of the pixel.
// The command is rate- and angle-limited, with a dead band against jitter.
//
// Determinism: offline, a command computed from frame N takes effect at frame
// N + actuationDelayFrames exactly (the synthetic rig's capture waits for it),
// so the outputs do not depend on threads or frames in flight.
#pragma once

#include "horopter/core/export.hpp"

#include <span>

#include "horopter/core/option_table.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>

#include "horopter/hardware/head.hpp"
#include "horopter/interaction/tracking.hpp"
#include "horopter/vision/geometry.hpp"

namespace horopter {

enum class PanTiltFormula { Atan2, Paper };

struct HOROPTER_API HeadControlOptions {
  PanTiltFormula formula = PanTiltFormula::Atan2;
  double lambda = 0.75;         // Paper: phi = d * lambda (1/m, empirical)
  double gain = 0.7;            // fraction of the angular error corrected per command, (0, 1]
  double deadbandRad = 0.035;   // errors below this (about 2 degrees) are left alone
  double maxRateRadPerS = 1.0;  // each axis
  hw::HeadLimits limits{-1.2, 1.2, -0.6, 0.6, false, 0, 0, 1.0};
  // Where the face is held vertically, as a fraction of the image height from
  // the top (0.5: centred). Above the centre keeps the hands in view.
  double faceRowFraction = 0.35;
  int imageHeight = 0;  // pixels (0: the face is centred)
  // Frame the gestures, not only the face: pan so that the middle of the
  // horizontal extent of the head and the tracked hands (left image) sits
  // where the face would, shifted from the face by at most
  // maxHandShiftFraction of the image's width (needs focalPx and
  // imageWidth). A hand stretched out sideways then stays where both views
  // see it: on the image's left the right view misses a band as wide as the
  // hand's disparity, so a hand there has no depth and no zone.
  // Off by default: the image then shifts under the hands' image-plane
  // tracks whenever a hand stretches out (tuning seeds 5000-5019: region loss
  // 7.1 -> 10.4 %, 5020-5039: 12.5 -> 12.4 %).
  bool frameHands = false;
  double maxHandShiftFraction = 0.25;
  int imageWidth = 0;
  double framesPerSecond = 30;         // the time between commands, for the rate limit
  int actuationDelayFrames = 3;        // >= 1: a command from frame N acts at frame N + delay
  double focalPx = 0, cx = 0, cy = 0;  // the rectified left camera (Paper; Atan2 fallback)
};

// Absolute pan and tilt that centre `rigPoint` (rig frame of a head at `pose`).
HOROPTER_API hw::HeadAngles anglesToCentre(const cv::Point3f& rigPoint, const hw::HeadAngles& pose);
// Where a still point seen at `pixel` of the rectified left image, `depthM`
// ahead of the rig, appears once the head has turned from pose `from` to
// pose `to` (both about the rig's origin, midway between the cameras). The
// pixel is returned unchanged when the point would lie behind the camera or
// the geometry is missing (focalPx or depth not positive).
HOROPTER_API cv::Point2f pixelAfterHeadTurn(cv::Point2f pixel, double depthM,
                                            const hw::HeadAngles& from, const hw::HeadAngles& to,
                                            const RectifiedGeometry& rig);
// The paper's formula: the angle to add to the pose for an offset `offsetPx`
// (pixels from the principal point) at distance `distanceM`.
HOROPTER_API double paperAngle(double offsetPx, double focalPx, double distanceM, double lambda);
// The next command from the pose at capture towards `target`: dead band,
// gain, rate limit over one frame, angle limits. Vergence is kept.
HOROPTER_API hw::HeadAngles limitCommand(const hw::HeadAngles& pose, const hw::HeadAngles& target,
                                         const HeadControlOptions& options);

// The head control's options a user tunes (flags, help, ranges, JSON keys); validation
// checks them against it.
HOROPTER_API std::span<const NumberOption<HeadControlOptions>> headControlOptions();

// Throws horopter::Error for options out of range.
HOROPTER_API void validate(const HeadControlOptions& options);

// Whether a frame's tracking asks for a head command: an elected godfather
// whose head was observed in this frame.
HOROPTER_API bool wantsHeadCommand(const TrackingState& state);

// The command that centres the godfather (wantsHeadCommand), from the head's
// pose at capture: std::nullopt when none is wanted, without the geometry
// (no depth and no focal length) or inside the dead band. The stage that
// posts it every frame is the application's (makeHeadControlStage).
HOROPTER_API std::optional<hw::HeadAngles> headCommand(const TrackingState& state,
                                                       const hw::HeadAngles& pose,
                                                       const HeadControlOptions& options);

}  // namespace horopter
