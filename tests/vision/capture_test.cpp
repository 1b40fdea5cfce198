// File-based capture sources and their errors; the vision stages through the
// scheduler give the same disparity as the front end called directly.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "horopter/app/vision_stages.hpp"
#include "horopter/core/error.hpp"
#include "horopter/sim/synthetic_source.hpp"
#include "horopter/vision/capture.hpp"
#include "horopter/vision/frontend.hpp"
#include "horopter/vision/opencv.hpp"
#include "test_support.hpp"

namespace horopter {
namespace {

namespace fs = std::filesystem;

// A random-dot pair: the right view is the left shifted by `shift` pixels.
std::pair<cv::Mat, cv::Mat> dotPair(int seed, int shift, cv::Size size = {96, 64}) {
  cv::Mat left(size, CV_8UC3);
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  rng.fill(left, cv::RNG::UNIFORM, 0, 256);
  cv::Mat right(size, CV_8UC3, cv::Scalar::all(0));
  left.colRange(shift, size.width).copyTo(right.colRange(0, size.width - shift));
  return {left, right};
}

fs::path freshDir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

using test::errorOf;

TEST(Capture, DirectorySourceReadsPairsInSortedOrder) {
  const fs::path dir = freshDir("horopter_dir_source");
  for (int i = 0; i < 3; ++i) {
    const auto [l, r] = dotPair(i, 4);
    cv::imwrite((dir / ("left" + std::to_string(i) + ".png")).string(), l);
    cv::imwrite((dir / ("right" + std::to_string(i) + ".png")).string(), r);
  }
  auto source = openSource("dir:" + dir.string(), {});
  Frame f;
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(source->next(f));
    EXPECT_EQ(cv::norm(f.left, dotPair(i, 4).first, cv::NORM_INF), 0) << i;
  }
  EXPECT_FALSE(source->next(f));
}

TEST(Capture, DirectorySourceTakesLeftAndRightSubfolders) {
  const fs::path dir = freshDir("horopter_dir_sub");
  fs::create_directories(dir / "left");
  fs::create_directories(dir / "right");
  const auto [l, r] = dotPair(7, 3);
  cv::imwrite((dir / "left" / "000.png").string(), l);
  cv::imwrite((dir / "right" / "000.png").string(), r);
  auto source = openSource("dir:" + dir.string(), {});
  Frame f;
  ASSERT_TRUE(source->next(f));
  EXPECT_EQ(cv::norm(f.right, r, cv::NORM_INF), 0);
  EXPECT_FALSE(source->next(f));
}

TEST(Capture, DirectorySourceErrorsSayWhatIsWrong) {
  EXPECT_NE(errorOf([] { openSource("dir:/no/such/folder", {}); }).find("does not exist"),
            std::string::npos);
  const fs::path empty = freshDir("horopter_dir_empty");
  EXPECT_NE(errorOf([&] { openSource("dir:" + empty.string(), {}); }).find("no stereo images"),
            std::string::npos);
  const fs::path odd = freshDir("horopter_dir_odd");
  const auto [l, r] = dotPair(1, 2);
  cv::imwrite((odd / "left0.png").string(), l);
  cv::imwrite((odd / "left1.png").string(), l);
  cv::imwrite((odd / "right0.png").string(), r);
  EXPECT_NE(errorOf([&] { openSource("dir:" + odd.string(), {}); }).find("2 left and 1 right"),
            std::string::npos);
  const fs::path mismatched = freshDir("horopter_dir_sizes");
  cv::imwrite((mismatched / "left0.png").string(), l);
  cv::imwrite((mismatched / "right0.png").string(), r(cv::Rect(0, 0, 50, 50)));
  auto source = openSource("dir:" + mismatched.string(), {});
  Frame f;
  EXPECT_NE(errorOf([&] { source->next(f); }).find("one size"), std::string::npos);
  const fs::path corrupt = freshDir("horopter_dir_corrupt");
  std::ofstream(corrupt / "left0.png") << "not a png";
  cv::imwrite((corrupt / "right0.png").string(), r);
  auto bad = openSource("dir:" + corrupt.string(), {});
  EXPECT_NE(errorOf([&] { bad->next(f); }).find("cannot read image"), std::string::npos);
}

TEST(Capture, DirectorySourcePairsImagesByNameInNaturalOrder) {
  const fs::path dir = freshDir("horopter_dir_names");
  // Written out of order, with names whose sorted text order differs.
  for (int i : {10, 2, 1}) {
    const auto [l, r] = dotPair(i, 4);
    cv::imwrite((dir / ("left_" + std::to_string(i) + ".png")).string(), l);
    cv::imwrite((dir / ("right_" + std::to_string(i) + ".png")).string(), r);
  }
  auto source = openSource("dir:" + dir.string(), {});
  Frame f;
  for (int i : {1, 2, 10}) {
    ASSERT_TRUE(source->next(f));
    EXPECT_EQ(cv::norm(f.left, dotPair(i, 4).first, cv::NORM_INF), 0) << i;
    EXPECT_EQ(cv::norm(f.right, dotPair(i, 4).second, cv::NORM_INF), 0) << i;
  }
  EXPECT_FALSE(source->next(f));
}

TEST(Capture, DirectorySourceNamesAnImageWithoutItsPartner) {
  const fs::path dir = freshDir("horopter_dir_unpaired");
  const auto [l, r] = dotPair(3, 2);
  cv::imwrite((dir / "left1.png").string(), l);
  cv::imwrite((dir / "left2.png").string(), l);
  cv::imwrite((dir / "right1.png").string(), r);
  cv::imwrite((dir / "right3.png").string(), r);
  const std::string message = errorOf([&] { openSource("dir:" + dir.string(), {}); });
  EXPECT_NE(message.find("left image 'left2.png' has no right image"), std::string::npos)
      << message;
  const fs::path twice = freshDir("horopter_dir_twice");
  cv::imwrite((twice / "left1.png").string(), l);
  cv::imwrite((twice / "left1.jpg").string(), l);
  cv::imwrite((twice / "right1.png").string(), r);
  EXPECT_NE(errorOf([&] { openSource("dir:" + twice.string(), {}); }).find("have one name"),
            std::string::npos);
}

TEST(Capture, VideoPairSourceReadsBothVideosFrameByFrame) {
  const fs::path dir = freshDir("horopter_video");
  const std::string lp = (dir / "l.avi").string(), rp = (dir / "r.avi").string();
  {
    cv::VideoWriter lw(lp, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10, {96, 64});
    cv::VideoWriter rw(rp, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10, {96, 64});
    ASSERT_TRUE(lw.isOpened() && rw.isOpened()) << "this OpenCV cannot write MJPG";
    for (int i = 0; i < 5; ++i) {
      const auto [l, r] = dotPair(i, 2);
      lw.write(l);
      rw.write(r);
    }
  }
  auto source = openSource("video:" + lp + "," + rp, {});
  Frame f;
  int frames = 0;
  while (source->next(f)) {
    EXPECT_EQ(f.left.size(), cv::Size(96, 64));
    ++frames;
  }
  EXPECT_EQ(frames, 5);
  EXPECT_NE(
      errorOf([&] { openSource("video:" + lp + ",/no/such.avi", {}); }).find("does not exist"),
      std::string::npos);
  EXPECT_NE(errorOf([&] { openSource("video:" + lp, {}); }).find("two comma-separated"),
            std::string::npos);
}

TEST(Capture, UnknownSpecsAndMissingCamerasAreClearErrors) {
  EXPECT_NE(errorOf([] { openSource("kinect", {}); }).find("unknown source 'kinect'"),
            std::string::npos);
  EXPECT_NE(errorOf([] {
              openSource("camera:/dev/no-video-98,/dev/no-video-99", {});
            }).find("does not exist"),
            std::string::npos);
  EXPECT_NE(errorOf([] { openSource("sbs:/dev/no-video-97", {}); }).find("does not exist"),
            std::string::npos);
}

TEST(Capture, PipelineFrontEndEqualsTheFrontEndCalledDirectly) {
  const fs::path dir = freshDir("horopter_pipeline_frontend");
  for (int i = 0; i < 4; ++i) {
    const auto [l, r] = dotPair(10 + i, 5 + i, {160, 96});
    cv::imwrite((dir / ("left" + std::to_string(i) + ".png")).string(), l);
    cv::imwrite((dir / ("right" + std::to_string(i) + ".png")).string(), r);
  }
  StereoParams stereo;
  stereo.numDisparities = 32;
  stereo.blockSize = 7;
  const MedianParams median;
  const std::vector<std::int16_t> thresholds(160, 5 * 16);

  std::vector<cv::Mat> direct;
  {
    StereoFrontend frontend(stereo, median, scalarBackend(), 1);
    for (int i = 0; i < 4; ++i) {
      const auto [l, r] = dotPair(10 + i, 5 + i, {160, 96});
      cv::Mat lg, rg;
      cv::cvtColor(l, lg, cv::COLOR_BGR2GRAY);
      cv::cvtColor(r, rg, cv::COLOR_BGR2GRAY);
      frontend.computeDisparity(viewOf(lg), viewOf(rg));
      frontend.computeMask(thresholds);
      direct.push_back(matOf(frontend.mask()).clone());
    }
  }
  for (int inFlight : {1, 3}) {
    PipelineOptions options;
    options.inFlight = inFlight;
    std::vector<cv::Mat> masks;
    options.onFrame = [&](const Frame& f) { masks.push_back(f.mask); };
    Pipeline pipeline(options);
    pipeline
        .add(makeRectifyStage(
            {}, [&](const Frame&, std::vector<std::int16_t>& out) { out = thresholds; }))
        .add(makeDisparityStage(stereo, median, scalarBackend(), 2))
        .add(makeMaskStage(stereo, scalarBackend()));
    auto source = frameSourceOf(openSource("dir:" + dir.string(), {}));
    pipeline.run(*source);
    ASSERT_EQ(masks.size(), 4u);
    for (int i = 0; i < 4; ++i)
      EXPECT_EQ(cv::norm(masks[i], direct[i], cv::NORM_INF), 0) << "frame " << i;
    EXPECT_GT(cv::countNonZero(masks[0]), 0);
  }
}

}  // namespace
}  // namespace horopter

namespace horopter {
namespace {

// The synthetic scene through the real stages: the same masks whatever the
// front end's thread count and the frames in flight.
TEST(Capture, SyntheticRunIsDeterministicAcrossThreadsAndDepth) {
  const StereoParams stereo;
  const Backend& backend = findBackend("auto");
  const auto runOnce = [&](int threads, int inFlight) {
    PipelineOptions options;
    options.inFlight = inFlight;
    std::vector<cv::Mat> masks;
    options.onFrame = [&](const Frame& f) { masks.push_back(f.mask); };
    Pipeline pipeline(options);
    pipeline
        .add(makeRectifyStage({},
                              [](const Frame& f, std::vector<std::int16_t>& out) {
                                out.assign(static_cast<std::size_t>(f.leftGrey.cols), 16 * 24);
                              }))
        .add(makeDisparityStage(stereo, MedianParams{}, backend, threads))
        .add(makeMaskStage(stereo, backend));
    sim::SyntheticSource source(synth::SceneOptions{}, 5);
    pipeline.run(source);
    return masks;
  };
  const auto reference = runOnce(1, 1);
  ASSERT_EQ(reference.size(), 5u);
  EXPECT_GT(cv::countNonZero(reference[0]), 1000);
  const auto other = runOnce(2, 3);
  ASSERT_EQ(other.size(), 5u);
  for (std::size_t i = 0; i < reference.size(); ++i)
    EXPECT_EQ(cv::norm(reference[i], other[i], cv::NORM_INF), 0) << "frame " << i;
}

}  // namespace
}  // namespace horopter
