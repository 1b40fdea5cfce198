// The renderer behind SyntheticScene: cameras from the head pose, the static
// room cached per (pan, tilt) for each view, people drawn over it each frame
// (only where they changed since the last frame when the head has not moved).
#pragma once

#include <vector>

#include "horopter/sim/synthetic_scene.hpp"
#include "synthetic/people.hpp"
#include "synthetic/primitives.hpp"
#include "synthetic/rasteriser.hpp"
#include "synthetic/row_intervals.hpp"

namespace horopter::synth {

class SceneRenderer {
 public:
  explicit SceneRenderer(const SceneOptions& options);  // options already validated

  SyntheticFrame render(int frameIndex, const HeadPose& head);
  // eye 0: left, 1: right.
  Camera camera(const HeadPose& head, int eye) const;

  double focalPx() const { return focal_; }
  double cx() const { return cx_; }
  double cy() const { return cy_; }

 private:
  void updateStatic(const HeadPose& head);
  // How many parts a frame's rows are split into (-1: OpenCV's choice).
  double stripes() const { return options_.threads > 0 ? options_.threads : -1.0; }
  void updateStaticTruth(const HeadPose& head);

  SceneOptions options_;
  double focal_, cx_, cy_;
  std::vector<Primitive> room_;
  std::vector<PersonParams> people_;
  Layer staticLayer_[2];
  // The last frame, kept to draw the next one incrementally: when the head
  // has not moved, only the rectangles of the people's primitives that
  // changed (where they were and where they are, row by row) are drawn again, over the
  // room, with every primitive; the rest of the image, depth and truth is
  // the same as in the last frame. frameValid_ is false until a full frame
  // is drawn for the current caches.
  Layer frame_[2];
  FrameTruth frameTruth_;
  std::vector<Primitive> framePrimitives_;
  RowIntervals redraw_[2], truthRows_;  // buffers of the incremental frame
  HeadPose frameHead_;
  bool frameValid_ = false;
  bool staticValid_ = false;
  double staticPan_ = 0, staticTilt_ = 0;
  // The room's pixel truth for the cached layers and one vergence.
  FrameTruth staticTruth_;
  bool staticTruthValid_ = false;
  double staticTruthVergence_ = 0;
  double maxStaticDisparityPx_ = 0;  // of the nearest room surface, left view
};

}  // namespace horopter::synth
