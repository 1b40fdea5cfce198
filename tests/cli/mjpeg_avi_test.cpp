// run.avi's file: what is written reads back (size, count, rate, content
// within JPEG's loss), a full disk or an absurd size is an error naming the
// file, and a frame of the wrong size is refused rather than muxed.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <string>

#include "horopter/core/error.hpp"
#include "mjpeg_avi.hpp"

namespace horopter::cli {
namespace {

std::string tempPath(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "horopter_mjpeg_avi_test";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

// A smooth picture that changes with i: JPEG keeps it within a few levels.
cv::Mat picture(cv::Size size, int i) {
  cv::Mat bgr(size, CV_8UC3);
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x)
      bgr.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<uchar>(x + i), static_cast<uchar>(y * 2),
                                          static_cast<uchar>(128 + 10 * i));
  return bgr;
}

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(MjpegAvi, WhatIsWrittenReadsBackAtItsSizeRateAndContent) {
  const std::string path = tempPath("content.avi");
  const cv::Size size(96, 64);
  {
    MjpegAviFile file(path, size, 25);
    for (int i = 0; i < 7; ++i)
      file.write(picture(size, i));
    EXPECT_EQ(file.frames(), 7);
    file.close();
    file.close();  // idempotent
  }
  cv::VideoCapture capture(path);
  ASSERT_TRUE(capture.isOpened()) << path;
  EXPECT_DOUBLE_EQ(capture.get(cv::CAP_PROP_FPS), 25);
  int frames = 0;
  for (cv::Mat f; capture.read(f); ++frames) {
    ASSERT_EQ(f.size(), size);
    cv::Mat diff;
    cv::absdiff(f, picture(size, frames), diff);
    const cv::Scalar mean = cv::mean(diff);
    EXPECT_LT(mean[0] + mean[1] + mean[2], 6.0) << "frame " << frames;
  }
  EXPECT_EQ(frames, 7);
}

TEST(MjpegAvi, AFullDiskIsAnErrorNamingTheFile) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full on this system";
  const std::string message = messageOf([] {
    MjpegAviFile file("/dev/full", cv::Size(320, 240), 30);
    for (int i = 0; i < 40; ++i)
      file.write(picture(cv::Size(320, 240), i));
    file.close();
  });
  EXPECT_NE(message.find("/dev/full"), std::string::npos) << message;
}

TEST(MjpegAvi, AbsurdSizesRatesAndFramesAreRefused) {
  const std::string path = tempPath("bad.avi");
  EXPECT_NE(messageOf([&] { MjpegAviFile(path, cv::Size(0, 10), 30); }).find("frame size"),
            std::string::npos);
  EXPECT_NE(messageOf([&] { MjpegAviFile(path, cv::Size(10, 10), 0); }).find("fps"),
            std::string::npos);
  EXPECT_NE(messageOf([&] { MjpegAviFile(path, cv::Size(10, 10), std::nan("")); }).find("fps"),
            std::string::npos);
  EXPECT_NE(messageOf([&] {
              MjpegAviFile("/nonexistent-folder/a.avi", cv::Size(8, 8), 30);
            }).find("/nonexistent-folder/a.avi"),
            std::string::npos);
  MjpegAviFile file(path, cv::Size(16, 16), 30);
  EXPECT_NE(messageOf([&] { file.write(picture(cv::Size(16, 8), 0)); }).find("not a BGR image"),
            std::string::npos);
  EXPECT_NE(messageOf([&] {
              file.write(cv::Mat(16, 16, CV_8UC1, cv::Scalar(0)));
            }).find("not a BGR image"),
            std::string::npos);
  file.close();
  EXPECT_NE(messageOf([&] { file.write(picture(cv::Size(16, 16), 0)); }).find("closed"),
            std::string::npos);
}

}  // namespace
}  // namespace horopter::cli
