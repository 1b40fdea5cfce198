// Laban Movement Analysis features, computed online from the godfather's
// head and hands (BodySample), after Rett's use of LMA for human-robot
// interaction. The paper's Table I relates the LMA parameters to physical
// quantities; here they are:
//
//   LMA component   parameter                     physical quantity (this file)
//   Space           displacement angle per plane  the direction of a part's
//                                                 displacement over `stepFrames`,
//                                                 quantised into 8 sectors in the
//                                                 frontal (x,y), sagittal (z,y) and
//                                                 horizontal (x,z) planes
//                   curvature                     the change of that direction
//                                                 between successive displacements
//   Time            speed, acceleration           |v|, |dv/dt| of each part
//   Shape           rising / sinking              vertical displacement of the
//                                                 head-hands triangle's incentre
//                                                 from the start (the last rest)
//                   growing / shrinking           the triangle perimeter's change
//   Body            which parts move              head, left and right hand moving
//                                                 relative to the sternum
//   Effort          Time: sudden / sustained      acceleration above / below a limit
//                   Space: direct / indirect      straightness of the recent path
//                   Flow: free / bound            jerk above / below a limit
//
// Coordinates are the rig frame (metres, x right, y down, z away from the
// robot). The hands are taken relative to the sternum, a point a fixed
// distance below the head, so walking and swaying cancel out. Where tracking
// has no depth for a part, its image position is back-projected at the
// head's (or the last known) depth with the camera's intrinsics.
#pragma once

#include "horopter/core/export.hpp"

#include <array>
#include <cstdint>
#include <deque>
#include <opencv2/core.hpp>

#include "horopter/interaction/body.hpp"

namespace horopter {

struct HOROPTER_API LmaOptions {
  // The left rectified camera (for back-projecting parts without depth).
  double focalPx = 554.2562584220407;  // the synthetic scene's 60 degree field of view at 640 px
  double cx = 319.5, cy = 239.5;
  double baselineM = 0.12;       // image positions are the left camera's: shifted by B/2 to the rig
  int stepFrames = 3;            // displacements are taken over this many frames
  int smoothFrames = 3;          // positions are averaged over this many frames first
  double stillSpeedMps = 0.15;   // below: the part is still (no displacement angle)
  double suddenAccelMps2 = 6.0;  // Effort Time: above: sudden
  double freeJerkMps3 = 120.0;   // Effort Flow: above: free
  double directStraightness = 0.8;  // Effort Space: net / path length above: direct
  double sternumBelowHeadM = 0.3;   // the sternum, below the head centre
  double reachM = 1.0;     // a hand further than this from the sternum is not the godfather's
  double holdHandS = 0.5;  // an untracked hand keeps its last place this long, then rests
};

// One part's kinematics this frame.
struct HOROPTER_API PartKinematics {
  bool valid = false;       // tracked, with enough history
  cv::Point3f position;     // relative to the sternum (head: absolute rig position)
  cv::Point3f velocity;     // m/s (hands: relative to the sternum)
  double speed = 0;         // m/s
  double acceleration = 0;  // m/s^2
  double jerk = 0;          // m/s^3
  double curvature = 0;     // radians between successive displacements (0..pi)
  bool moving = false;      // speed >= LmaOptions::stillSpeedMps
  // Displacement direction, 0..7 (sector k covers [k*45-22.5, k*45+22.5)
  // degrees, 0 = +first axis, counter-clockwise towards the second), or -1
  // when the part is still. Planes: frontal (x, -y), sagittal (-z, -y),
  // horizontal (x, -z): "up" and "towards the robot" count positive.
  int frontalSector = -1, sagittalSector = -1, horizontalSector = -1;
};

enum class ShapeFlow { Stable, Growing, Shrinking };
enum class EffortTime { Sustained, Sudden };
enum class EffortSpace { Direct, Indirect };
enum class EffortFlow { Bound, Free };

// The discrete evidence the classifier uses, one symbol per variable.
enum class LmaSymbol {
  ActiveHand,        // 0 none, 1 left, 2 right
  FrontalSector,     // active hand: 0..7, 8 = still
  SagittalSector,    // active hand: 0..7, 8 = still
  HorizontalSector,  // active hand: 0..7, 8 = still
  Speed,             // active hand: 5 bins
  Curvature,         // active hand: 0 still, then 4 bins of the angle
  Height,            // active hand above/below the head: 6 bins
  Lateral,           // active hand outwards from the body's midline: 5 bins
  Reach,             // active hand towards the robot from the sternum: 5 bins
  IncentreRise,      // Shape: 5 bins
  Perimeter,         // Shape: 0 shrinking, 1 stable, 2 growing
  Body,              // moving parts: bit 0 head, 1 left hand, 2 right hand
  Time,              // Effort: 0 sustained, 1 sudden
  Space,             // Effort: 0 direct, 1 indirect
  Flow,              // Effort: 0 bound, 1 free
};
inline constexpr int kLmaSymbolCount = 15;
// The number of values each symbol takes, and its name (for the model file).
HOROPTER_API int lmaSymbolCardinality(LmaSymbol symbol);
HOROPTER_API const char* lmaSymbolName(LmaSymbol symbol);

struct HOROPTER_API LmaFeatures {
  bool valid = false;  // a godfather with head and hands tracked, enough history
  PartKinematics head, leftHand, rightHand;
  int activeHand = 0;        // 0 none, 1 left, 2 right (the person's own)
  double incentreRiseM = 0;  // Shape: incentre's rise since the last rest, metres (up > 0)
  double perimeterRate = 0;  // Shape: relative perimeter change per second
  ShapeFlow shape = ShapeFlow::Stable;
  unsigned movingParts = 0;  // Body: bit 0 head, 1 left hand, 2 right hand
  EffortTime time = EffortTime::Sustained;
  EffortSpace space = EffortSpace::Direct;
  EffortFlow flow = EffortFlow::Bound;
  std::array<std::uint8_t, kLmaSymbolCount> symbols{};  // meaningful when valid
};

// Quantises an angle (radians, any value) into 8 sectors of 45 degrees
// centred on 0, 45, ..., 315 degrees.
HOROPTER_API int angleSector(double angleRad);

// Online: one update per frame, in order. A frame without a godfather (or
// without the head tracked) gives invalid features and starts the history
// again. A hand without a track keeps its last place for holdHandS, then
// hangs at rest.
class HOROPTER_API LmaExtractor {
 public:
  explicit LmaExtractor(LmaOptions options = {});
  LmaFeatures update(const BodySample& sample);
  void reset();
  const LmaOptions& options() const { return options_; }

 private:
  struct Entry {
    double timeS = 0;
    cv::Point3d head, left, right;  // raw rig positions
  };
  struct Smoothed {
    double timeS = 0;
    cv::Point3d head, left, right;  // smoothed; hands relative to the sternum
  };
  struct HandMemory {
    bool valid = false;
    double seenS = 0;
    cv::Point3d offset;  // from the head
  };
  bool toRig(const PartState& part, double depthHint, cv::Point3d& out) const;

  LmaOptions options_;
  std::deque<Entry> raw_;
  std::deque<Smoothed> history_;
  HandMemory leftMemory_, rightMemory_;
  double lastHeadDepth_ = 0;
  bool haveRest_ = false;
  double restIncentreY_ = 0;  // incentre relative to the head at the last rest
  int restFrames_ = 0;
};

}  // namespace horopter
