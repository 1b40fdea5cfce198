// The renderer's images against the plainest ray caster: every pixel's ray
// tested against every primitive in drawing order (the room, then the
// people), the first strictly nearest surface shaded. The rasteriser's
// shortcuts (screen rectangles, capsule row spans, paired capsule tests,
// one shading per pixel, the cached room, incremental frames) must leave
// the same image, bit for bit.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <limits>
#include <string>
#include <vector>

#include "horopter/sim/synthetic_scene.hpp"
#include "synthetic/people.hpp"
#include "synthetic/primitives.hpp"
#include "synthetic/rasteriser.hpp"
#include "synthetic/room.hpp"
#include "synthetic/scene_renderer.hpp"
#include "synthetic/shading.hpp"

namespace horopter::synth {
namespace {

cv::Mat referenceImage(const Camera& camera, std::vector<Primitive> primitives) {
  for (Primitive& p : primitives)
    prepare(p, camera.centre);
  cv::Mat image(camera.height, camera.width, CV_8UC3);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      Ray ray;
      ray.o = camera.centre;
      ray.d = camera.rigToWorld.apply(
          Vec3{(x - camera.cx) / camera.f, (y - camera.cy) / camera.f, 1.0});
      double depth = std::numeric_limits<double>::infinity();
      const Primitive* winner = nullptr;
      Hit best;
      for (const Primitive& p : primitives) {
        Hit hit;
        if (!intersect(p, ray, depth, hit)) continue;
        depth = hit.t;
        best = hit;
        winner = &p;
      }
      cv::Vec3b& out = image.at<cv::Vec3b>(y, x);
      out = cv::Vec3b(0, 0, 0);
      if (!winner) continue;
      const cv::Vec3f c =
          shade(*winner, best, texture(winner->materials[best.face].texture), 1.0 / camera.f);
      out = cv::Vec3b(cv::saturate_cast<uchar>(c[0]), cv::saturate_cast<uchar>(c[1]),
                      cv::saturate_cast<uchar>(c[2]));
    }
  return image;
}

// Frames 44-47 of seed 4: the main person ends the walk (every part moves),
// the distractor sways; the head turns once in between (a full frame), then
// stays (incremental frames).
TEST(SyntheticReference, FramesEqualThePlainRayCaster) {
  SceneOptions o;
  o.width = 240;
  o.height = 180;
  o.seed = 4;
  o.skinClutter = true;
  o.pixelTruth = false;
  SceneRenderer renderer(o);
  const std::vector<Primitive> room = room::build(true, true);
  const std::vector<PersonParams> people = makePeople(o.seed, o.distractor, o.personDistanceM);
  HeadPose head = o.initialHead;
  int comparedPixels = 0, peoplePixels = 0;
  for (int index = 44; index < 48; ++index) {
    if (index == 45) head.pan = 0.05, head.tilt = -0.03;
    const SyntheticFrame frame = renderer.render(index, head);
    std::vector<Primitive> scene = room;
    std::vector<Primitive> onlyRoom = room;
    for (const PersonParams& p : people)
      addPrimitives(p, poseAt(p, index / o.framesPerSecond), scene);
    for (int eye = 0; eye < 2; ++eye) {
      const Camera camera = renderer.camera(head, eye);
      const cv::Mat expected = referenceImage(camera, scene);
      const cv::Mat& got = eye == 0 ? frame.left : frame.right;
      ASSERT_EQ(got.size(), expected.size());
      EXPECT_EQ(cv::norm(got, expected, cv::NORM_INF), 0)
          << "frame " << index << " eye " << eye << ": "
          << cv::countNonZero(cv::Mat(got != expected).reshape(1)) << " channel values differ";
      comparedPixels += expected.rows * expected.cols;
      // The people must be in view for the test to mean something.
      peoplePixels +=
          cv::countNonZero(cv::Mat(expected != referenceImage(camera, onlyRoom)).reshape(1));
    }
  }
  EXPECT_EQ(comparedPixels, 8 * 240 * 180);
  EXPECT_GT(peoplePixels, 2000) << "the people were hardly in view";
}

}  // namespace
}  // namespace horopter::synth
