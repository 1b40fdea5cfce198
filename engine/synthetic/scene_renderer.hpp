// The renderer behind SyntheticScene: cameras from the head pose, the static
// room cached per (pan, tilt) for each view, people drawn over it each frame.
#pragma once

#include <vector>

#include "horopter/synthetic_scene.hpp"
#include "synthetic/people.hpp"
#include "synthetic/primitives.hpp"
#include "synthetic/rasteriser.hpp"

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

  SceneOptions options_;
  double focal_, cx_, cy_;
  std::vector<Primitive> room_;
  std::vector<PersonParams> people_;
  Layer staticLayer_[2];
  bool staticValid_ = false;
  double staticPan_ = 0, staticTilt_ = 0;
};

}  // namespace horopter::synth
