// Detection on rendered frames of the synthetic scene, with its exact zone
// as the mask: inside the region only the zone's faces and hands, over the
// full image the distractor too; and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "horopter/core/error.hpp"
#include "horopter/eval/tracking_eval.hpp"
#include "horopter/interaction/detection.hpp"
#include "horopter/sim/sim_frame.hpp"
#include "horopter/sim/synthetic_scene.hpp"

namespace horopter {
namespace {

bool texturesPresent() {
  for (const synth::TextureSource& t : synth::textureSources())
    if (t.name == "astronaut" && !t.found) return false;
  return std::filesystem::exists(kDefaultFaceCascade);
}

sim::SimFrame renderedFrame(int index) {
  synth::SyntheticScene scene(synth::SceneOptions{});
  synth::SyntheticFrame f = scene.render(index);
  sim::SimFrame frame;
  frame.index = index;
  frame.left = f.left;
  frame.right = f.right;
  frame.mask = f.truth.inside.clone();
  frame.truth = f.truth;
  return frame;
}

bool near(cv::Point2f a, cv::Point2f b, double tolerance) {
  return std::hypot(double(a.x - b.x), double(a.y - b.y)) <= tolerance;
}

TEST(Detection, RegionFindsTheFaceInsideTheZoneOnly) {
  if (!texturesPresent())
    GTEST_SKIP() << "opencv-data or python3-skimage missing (scripts/setup.sh)";
  const sim::SimFrame frame = renderedFrame(100);
  const auto& truth = frame.truth;
  const synth::PersonTruth& main = truth.people[0];
  ASSERT_TRUE(main.insideZone && main.visible);
  Detector detector(DetectorOptions{});
  const Detections d = detector.detect(frame);
  ASSERT_FALSE(d.faces.empty());
  for (const FaceDetection& f : d.faces) {
    EXPECT_TRUE(f.insideZone);
    EXPECT_TRUE(near(f.centre, main.head2d, 0.5 * main.faceWidthPx)) << f.box;
  }
  for (const HandDetection& h : d.hands) {
    EXPECT_TRUE(h.insideZone);
    EXPECT_FALSE(near(h.centroid, main.head2d, 0.4 * main.faceWidthPx)) << "the face is not a hand";
  }
  EXPECT_LT(d.searchedPixels, frame.left.total() / 2) << "the region is smaller than the image";
}

TEST(Detection, FullImageSeesMoreThanTheZone) {
  if (!texturesPresent())
    GTEST_SKIP() << "opencv-data or python3-skimage missing (scripts/setup.sh)";
  const sim::SimFrame frame = renderedFrame(100);
  DetectorOptions region, full;
  full.scope = DetectionScope::FullImage;
  const Detections r = Detector(region).detect(frame);
  const Detections f = Detector(full).detect(frame);
  EXPECT_EQ(f.searchedPixels, static_cast<std::int64_t>(frame.left.total()));
  // The skin-coloured furniture and posters, and the distractor, are outside the zone.
  EXPECT_GT(f.hands.size(), r.hands.size());
  bool outside = false;
  for (const HandDetection& h : f.hands)
    outside |= !h.insideZone;
  EXPECT_TRUE(outside);
}

// Between full searches the cascade looks only around the previous frame's
// faces: the next frames still find the face where a full search does.
TEST(Detection, FollowingFindsTheFaceAFullSearchFinds) {
  if (!texturesPresent())
    GTEST_SKIP() << "opencv-data or python3-skimage missing (scripts/setup.sh)";
  DetectorOptions followOptions;
  followOptions.fullSearchEvery = 5;
  Detector following(followOptions), full(DetectorOptions{});
  for (int index = 100; index < 104; ++index) {
    const sim::SimFrame frame = renderedFrame(index);
    const Detections a = following.detect(frame), b = full.detect(frame);
    ASSERT_FALSE(b.faces.empty()) << "frame " << index;
    ASSERT_EQ(a.faces.size(), b.faces.size()) << "frame " << index;
    for (std::size_t i = 0; i < a.faces.size(); ++i)
      EXPECT_TRUE(near(a.faces[i].centre, b.faces[i].centre, 0.25 * b.faces[i].width))
          << "frame " << index << ": " << a.faces[i].box << " vs " << b.faces[i].box;
  }
}

// A full search guided by skin (only around the zone's skin blobs) finds
// the face an exhaustive search finds.
TEST(Detection, SkinGuidedSearchFindsTheFaceTheExhaustiveSearchFinds) {
  if (!texturesPresent())
    GTEST_SKIP() << "opencv-data or python3-skimage missing (scripts/setup.sh)";
  DetectorOptions guidedOptions, exhaustiveOptions;
  guidedOptions.fullSearchEvery = exhaustiveOptions.fullSearchEvery = 1;
  guidedOptions.exhaustiveSearchEvery = 0;
  exhaustiveOptions.exhaustiveSearchEvery = 1;
  Detector guided(guidedOptions), exhaustive(exhaustiveOptions);
  for (int index = 100; index < 103; ++index) {
    const sim::SimFrame frame = renderedFrame(index);
    const Detections a = guided.detect(frame), b = exhaustive.detect(frame);
    EXPECT_TRUE(a.fullFaceSearch && b.fullFaceSearch);
    ASSERT_EQ(b.faces.size(), 1u) << "frame " << index;
    ASSERT_EQ(a.faces.size(), 1u) << "frame " << index;
    EXPECT_TRUE(near(a.faces[0].centre, b.faces[0].centre, 0.25 * b.faces[0].width))
        << "frame " << index << ": " << a.faces[0].box << " vs " << b.faces[0].box;
  }
}

// Faces sized by depth: once a few faces have given the width per
// disparity, the cascade searches only the sizes the zone's disparities
// allow, and still finds the face.
TEST(Detection, FacesSizedByDepthStillFound) {
  if (!texturesPresent())
    GTEST_SKIP() << "opencv-data or python3-skimage missing (scripts/setup.sh)";
  Detector detector(DetectorOptions{});
  for (int index = 100; index < 106; ++index) {
    sim::SimFrame frame = renderedFrame(index);
    const auto& truth = frame.truth;
    frame.disparity = truth.disparity;
    const Detections d = detector.detect(frame);
    ASSERT_EQ(d.faces.size(), 1u) << "frame " << index;
    EXPECT_TRUE(near(d.faces[0].centre, truth.people[0].head2d, 0.5 * truth.people[0].faceWidthPx));
    if (index >= 103) {
      ASSERT_GT(d.faceSizes.height, 0) << "no size limit after " << index - 100 << " faces";
      EXPECT_LE(d.faceSizes.width, d.faces[0].width);
      EXPECT_GE(d.faceSizes.height, d.faces[0].width);
    }
  }
}

// Following sized and placed by the face: a face moving 12 px a frame
// (frame 100 shifted) leaves a window of 0.1 face widths around where it
// was, but not the one around where its last step takes it. After the
// first step is known (one frame's miss brings a full search), following
// finds it every frame without a full search, where the full search does.
TEST(Detection, FollowingLooksWhereTheFacesStepTakesIt) {
  if (!texturesPresent())
    GTEST_SKIP() << "opencv-data or python3-skimage missing (scripts/setup.sh)";
  DetectorOptions o;
  o.fullSearchEvery = 1000;
  o.followSlackFaces = 0.1;
  // At followFacePx 36 (the default) the cascade misses this face in a
  // follow window now and then, moving or not (a miss costs a full search,
  // not the face): the window's placement is tested at faceScale.
  o.followFacePx = 0;
  ASSERT_GT(o.followSizeRatio, 0);
  Detector following(o), full(DetectorOptions{});
  const sim::SimFrame still = renderedFrame(100);
  for (int k = 0; k < 6; ++k) {
    sim::SimFrame frame = still;
    frame.left = cv::Mat();  // not into still's pixels
    frame.mask = cv::Mat();
    const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, 12 * k, 0, 1, 0);
    cv::warpAffine(still.left, frame.left, shift, still.left.size(), cv::INTER_NEAREST,
                   cv::BORDER_REPLICATE);
    cv::warpAffine(still.mask, frame.mask, shift, still.mask.size(), cv::INTER_NEAREST);
    const Detections a = following.detect(frame), b = full.detect(frame);
    ASSERT_EQ(b.faces.size(), 1u) << "step " << k;
    ASSERT_EQ(a.faces.size(), 1u) << "step " << k;
    EXPECT_TRUE(near(a.faces[0].centre, b.faces[0].centre, 0.25 * b.faces[0].width))
        << "step " << k << ": " << a.faces[0].box << " vs " << b.faces[0].box;
    if (k >= 2) {
      EXPECT_FALSE(a.fullFaceSearch) << "step " << k << ": the window missed the face";
    }
  }
}

// The rectify stage's grey image, where the frame has one, is the colour
// image converted as the cascade would: the same faces either way.
TEST(Detection, FacesFromTheFramesGreyImageAreTheSame) {
  if (!texturesPresent())
    GTEST_SKIP() << "opencv-data or python3-skimage missing (scripts/setup.sh)";
  Detector withGrey(DetectorOptions{}), withoutGrey(DetectorOptions{});
  for (int index = 100; index < 106; ++index) {
    sim::SimFrame frame = renderedFrame(index);
    const Detections b = withoutGrey.detect(frame);
    cv::cvtColor(frame.left, frame.leftGrey, cv::COLOR_BGR2GRAY);
    const Detections a = withGrey.detect(frame);
    ASSERT_FALSE(b.faces.empty()) << index;
    ASSERT_EQ(a.faces.size(), b.faces.size()) << index;
    for (std::size_t i = 0; i < a.faces.size(); ++i)
      EXPECT_EQ(a.faces[i].box, b.faces[i].box) << index;
  }
}

// A skin disc on a textured background, rendered as a stereo pair: where the
// disparity map is right the views agree on the disc; where it claims the
// disc is nearer than it is (block matching's fattened silhouette), they do
// not. Its inscribed radius is the disc's.
TEST(Detection, HandCandidatesCarryStereoAgreementAndRadius) {
  if (!std::filesystem::exists(kDefaultFaceCascade)) GTEST_SKIP() << "opencv-data missing";
  const int w = 200, h = 120;
  cv::Mat texture(h, w + 40, CV_8UC3);
  cv::RNG rng(7);
  rng.fill(texture, cv::RNG::UNIFORM, cv::Scalar(20, 20, 20), cv::Scalar(90, 90, 90));
  // Skin chroma with a strong texture in brightness (the chroma of a colour
  // scaled by f stays in the skin box for f in 0.6..1.2).
  cv::Mat skin(h, w + 40, CV_8UC3);
  for (int y = 0; y < skin.rows; ++y)
    for (int x = 0; x < skin.cols; ++x) {
      const double f = rng.uniform(0.6, 1.2);
      skin.at<cv::Vec3b>(y, x) = cv::Vec3b(cv::saturate_cast<std::uint8_t>(110 * f),
                                           cv::saturate_cast<std::uint8_t>(140 * f),
                                           cv::saturate_cast<std::uint8_t>(200 * f));
    }
  // The scene seen from the left at x: the disc A at disparity 12, the disc B
  // (a patch of the far wall) and the background at disparity 2.
  const cv::Point a(60, 60), b(150, 60);
  const int r = 15;
  Frame frame;
  frame.left.create(h, w, CV_8UC3);
  frame.right.create(h, w, CV_8UC3);
  frame.disparity.create(h, w, CV_16SC1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool inA = cv::norm(cv::Point(x, y) - a) <= r, inB = cv::norm(cv::Point(x, y) - b) <= r;
      frame.left.at<cv::Vec3b>(y, x) =
          (inA || inB) ? skin.at<cv::Vec3b>(y, x + 20) : texture.at<cv::Vec3b>(y, x + 20);
      // B claims disparity 12 although it lies at 2.
      frame.disparity.at<std::int16_t>(y, x) =
          static_cast<std::int16_t>(16 * (inA || inB ? 12 : 2));
    }
  // The right view: each left pixel x at disparity d shows at x - d.
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      // What the right camera sees at x: A where x + 12 is in A, else the
      // background and B (both at disparity 2) at x + 2.
      const bool aHere = cv::norm(cv::Point(x + 12, y) - a) <= r;
      const bool bHere = cv::norm(cv::Point(x + 2, y) - b) <= r;
      frame.right.at<cv::Vec3b>(y, x) = aHere   ? skin.at<cv::Vec3b>(y, x + 12 + 20)
                                        : bHere ? skin.at<cv::Vec3b>(y, x + 2 + 20)
                                                : texture.at<cv::Vec3b>(y, x + 2 + 20);
    }
  cv::cvtColor(frame.left, frame.leftGrey, cv::COLOR_BGR2GRAY);
  cv::cvtColor(frame.right, frame.rightGrey, cv::COLOR_BGR2GRAY);
  frame.mask = cv::Mat(h, w, CV_8UC1, cv::Scalar(255));
  DetectorOptions o;
  o.minFacePx = 40;
  const Detections d = Detector(o).detect(frame);
  const HandDetection *onA = nullptr, *onB = nullptr;
  for (const HandDetection& c : d.hands) {
    if (near(c.centroid, a, 3)) onA = &c;
    if (near(c.centroid, b, 3)) onB = &c;
  }
  ASSERT_TRUE(onA && onB) << d.hands.size() << " candidates";
  EXPECT_GT(onA->stereoAgreement, 0.9f);
  EXPECT_LT(onB->stereoAgreement, 0.5f);
  // The eroded zone (4 px at 200 wide: 1 px) leaves the disc nearly whole.
  EXPECT_NEAR(onA->radiusPx, r, 3);
  // Its mean grey level is the disc's.
  cv::Mat grey, disc = cv::Mat::zeros(h, w, CV_8UC1);
  cv::cvtColor(frame.left, grey, cv::COLOR_BGR2GRAY);
  cv::circle(disc, a, r - 2, cv::Scalar(255), cv::FILLED);
  EXPECT_NEAR(onA->meanLuma, cv::mean(grey, disc)[0], 8);
  // Over the full image nothing is measured.
  o.scope = DetectionScope::FullImage;
  for (const HandDetection& c : Detector(o).detect(frame).hands)
    EXPECT_EQ(c.stereoAgreement, 1.0f);
}

// Tuning seed 10048 (issue 20): a face width per disparity learnt from a
// false face in the zone, before the person came, kept the real face out of
// the sizes searched, and the person was never elected. Forgotten after
// depthSizeForgetSearches empty searches, the face is found. The whole
// trial's front end, as eval-tracking runs it.
TEST(Detection, AFaceSizeLearntFromAFalseFaceDoesNotHideTheRealOne) {
  if (!texturesPresent())
    GTEST_SKIP() << "opencv-data or python3-skimage missing (scripts/setup.sh)";
  const auto framesWithTheFace = [](int forgetAfter) {
    TrialOptions trial;
    trial.seed = 10048;
    trial.frames = 110;  // the person is inside the zone from about frame 86
    trial.detector.depthSizeForgetSearches = forgetAfter;
    int found = 0;
    runTrackingTrial(trial, DetectionScope::HoropterRegion, {}, [&](const TrialFrame& t) {
      for (const FaceDetection& f : t.frame.detections->faces)
        if (f.insideZone &&
            near(f.centre, t.truth.people[0].head2d, 0.5 * t.truth.people[0].faceWidthPx))
          ++found;
    });
    return found;
  };
  EXPECT_LE(framesWithTheFace(1000000), 2);  // a frame here and there
  EXPECT_GT(framesWithTheFace(DetectorOptions{}.depthSizeForgetSearches), 10);
}

// Tuning seed 10486 (issue 20): the cascade found a "face" on a shirt of
// skin's chroma, 2.5 face widths under the head at the torso's depth, with
// half the face's grey level. Taken for a face, it gave the skin's reference
// luma (so the sleeves stayed skin) and its neck cut took in the right hand
// at rest: the trial lost 69 % of its frames, the right hand 53 %. On the
// followed head's body it is no face (body_face.hpp). The trial's first
// half, as eval-tracking runs it, with and without that rule.
TEST(Detection, AFalseFaceOnTheShirtIsNoFace) {
  if (!texturesPresent())
    GTEST_SKIP() << "opencv-data or python3-skimage missing (scripts/setup.sh)";
  struct Outcome {
    TrialResult result;
    int falseFaces = 0;  // faces found 1.5 face widths or more under the head
    int setApart = 0;    // ... of them, set apart as body faces
  };
  const auto run = [](bool bodyFaceRule) {
    TrialOptions trial;
    trial.seed = 10486;
    trial.frames = 150;  // elected at frame 93; the false face from frame 70
    if (!bodyFaceRule) {
      trial.detector.bodyFaceBelowFaces = 0;
      trial.detector.bodyFaceDarkFraction = 0;
    }
    Outcome out;
    const auto under = [](const FaceDetection& f, const synth::PersonTruth& p) {
      return f.centre.y - p.head2d.y >= 1.5 * p.faceWidthPx;
    };
    out.result =
        runTrackingTrial(trial, DetectionScope::HoropterRegion, {}, [&](const TrialFrame& t) {
          const synth::PersonTruth& p = t.truth.people[0];
          for (const FaceDetection& f : t.frame.detections->faces)
            out.falseFaces += under(f, p);
          for (const FaceDetection& f : t.frame.detections->bodyFaces) {
            out.falseFaces += under(f, p);
            out.setApart += under(f, p);
          }
        });
    return out;
  };
  const Outcome with = run(true), without = run(false);
  const auto show = [](const Outcome& o) {
    return ::testing::Message() << o.falseFaces << " false faces, " << o.setApart
                                << " set apart; right hand lost " << o.result.rightHand.lost
                                << " of " << o.result.rightHand.visible << ", trial loss "
                                << o.result.trackerLoss();
  };
  SCOPED_TRACE(::testing::Message() << "with: " << show(with) << "; without: " << show(without));
  EXPECT_GT(without.falseFaces, 20);
  EXPECT_EQ(without.setApart, 0);
  EXPECT_GT(without.result.rightHand.lost, 20);
  EXPECT_GT(without.result.trackerLoss(), 0.4);
  EXPECT_GT(with.falseFaces, 20);             // still found,
  EXPECT_EQ(with.setApart, with.falseFaces);  // but no face
  EXPECT_LE(with.result.rightHand.lost, 5);
  EXPECT_LT(with.result.trackerLoss(), 0.2);
}

// Tuning seed 10146: a khaki shirt of skin's chroma whose sleeves, at
// 0.58-0.68 of the face's grey level, pass the face-relative cut; the left
// hand at rest joins its sleeve into one blob 40-60 px up the arm, and the
// trial lost 97 % of its frames. The chest under the head shows the cloth's
// own level (shirt_skin.hpp). The trial's first half, as eval-tracking runs
// it, with and without that rule.
TEST(Detection, TheSleeveOfASkinColouredShirtIsNoHand) {
  if (!texturesPresent())
    GTEST_SKIP() << "opencv-data or python3-skimage missing (scripts/setup.sh)";
  const auto run = [](bool shirtRule) {
    TrialOptions trial;
    trial.seed = 10146;
    trial.frames = 150;
    if (!shirtRule) trial.detector.shirtLumaOfTorso = 0;
    return runTrackingTrial(trial, DetectionScope::HoropterRegion, {}, {});
  };
  const TrialResult with = run(true), without = run(false);
  SCOPED_TRACE(::testing::Message()
               << "left hand lost, with: " << with.leftHand.lost << " of " << with.leftHand.visible
               << ", without: " << without.leftHand.lost << " of " << without.leftHand.visible);
  EXPECT_GT(without.leftHand.visible, 30);
  EXPECT_GT(without.leftHand.lost, without.leftHand.visible / 2);
  EXPECT_GT(without.trackerLoss(), 0.5);
  EXPECT_LE(with.leftHand.lost, 5);
  EXPECT_LT(with.trackerLoss(), 0.1);
}

// A face width per disparity learnt wrong (here: the disparities made four times larger
// after it was learnt) bounds the sizes away from the real face; after
// depthSizeForgetSearches empty searches it is forgotten and the face found.
TEST(Detection, AWrongFaceSizeFromDepthIsForgotten) {
  if (!texturesPresent())
    GTEST_SKIP() << "opencv-data or python3-skimage missing (scripts/setup.sh)";
  const auto framesToFindAgain = [](int forgetAfter) {
    DetectorOptions o;
    o.depthSizeForgetSearches = forgetAfter;
    Detector detector(o);
    for (int index = 100; index < 104; ++index) {  // k learnt from the truth
      sim::SimFrame frame = renderedFrame(index);
      frame.disparity = frame.truth.disparity;
      EXPECT_EQ(detector.detect(frame).faces.size(), 1u) << index;
    }
    for (int k = 1; k <= 14; ++k) {
      sim::SimFrame frame = renderedFrame(104 + k);
      frame.disparity = frame.truth.disparity * 4;
      if (!detector.detect(frame).faces.empty()) return k;
    }
    return 0;  // never
  };
  const int forgetting = framesToFindAgain(10);
  EXPECT_GE(forgetting, 10);  // the larger disparities did keep the face out
  EXPECT_LE(forgetting, 11);
  EXPECT_EQ(framesToFindAgain(1000), 0);
}

// Skin-coloured cloth is far darker than skin under the same light: with the
// face's skin luma known, skin darker than a fraction of it is no hand.
TEST(Detection, SkinDarkerThanTheFaceIsNotAHand) {
  if (!texturesPresent())
    GTEST_SKIP() << "opencv-data or python3-skimage missing (scripts/setup.sh)";
  const sim::SimFrame frame = renderedFrame(100);
  DetectorOptions o;
  o.minSkinLumaOfFace = 0;
  const Detections all = Detector(o).detect(frame);
  ASSERT_EQ(all.faces.size(), 1u);
  EXPECT_GT(all.faces[0].skinLuma, 40.f);
  ASSERT_FALSE(all.hands.empty());
  for (const HandDetection& h : all.hands)
    EXPECT_GT(h.meanLuma, 0.f);
  o.minSkinLumaOfFace = 3;  // brighter than any skin under this light
  EXPECT_TRUE(Detector(o).detect(frame).hands.empty());
}

TEST(Detection, BadInputIsAnError) {
  if (!std::filesystem::exists(kDefaultFaceCascade)) GTEST_SKIP() << "opencv-data missing";
  // Each entry spoils one option of the defaults.
  const std::vector<std::function<void(DetectorOptions&)>> spoilers = {
      [](DetectorOptions& o) { o.faceCascade = "/nonexistent/cascade.xml"; },
      [](DetectorOptions& o) { o.scaleFactor = 1.0; },
      [](DetectorOptions& o) { o.fullSearchEvery = 0; },
      [](DetectorOptions& o) { o.exhaustiveSearchEvery = -1; },
      [](DetectorOptions& o) { o.followSizeRatio = 0.5; },
      [](DetectorOptions& o) { o.followSlackFaces = -1; },
      [](DetectorOptions& o) { o.followFacePx = 20; },
      [](DetectorOptions& o) { o.acquisitionFaceScale = 2; },
      [](DetectorOptions& o) { o.faceZoneCover = 1.5; },
      [](DetectorOptions& o) { o.minSkinLumaOfFace = -0.1; },
      [](DetectorOptions& o) { o.bodyFaceBelowFaces = -1; },
      [](DetectorOptions& o) { o.bodyFaceDarkFraction = 1.5; },
      [](DetectorOptions& o) { o.bodyFaceMemoryFrames = -1; },
      [](DetectorOptions& o) { o.depthSizeForgetSearches = 0; },
  };
  for (std::size_t i = 0; i < spoilers.size(); ++i) {
    DetectorOptions o;
    spoilers[i](o);
    EXPECT_THROW(Detector{o}, Error) << "bad option #" << i;
  }
  Detector detector(DetectorOptions{});
  Frame frame;
  frame.left = cv::Mat(48, 64, CV_8UC3, cv::Scalar::all(90));
  EXPECT_THROW(detector.detect(frame), Error) << "the region needs the mask";
  frame.mask = cv::Mat(10, 10, CV_8UC1, cv::Scalar(0));
  EXPECT_THROW(detector.detect(frame), Error) << "mask of another size";
  frame.mask = cv::Mat(48, 64, CV_8UC1, cv::Scalar(0));
  EXPECT_TRUE(detector.detect(frame).faces.empty()) << "an empty zone holds nothing";
}

}  // namespace
}  // namespace horopter
