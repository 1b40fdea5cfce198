// run.avi's recorder: every view handed over is in the video (the encoder
// thread drains its queue at close), a view of another size is resized
// rather than dropped, the scale divides the size, and a file that cannot
// be written is an error naming it.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/videoio.hpp>
#include <string>

#include "horopter/core/error.hpp"
#include "video_recorder.hpp"

namespace horopter::cli {
namespace {

std::string tempPath(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "horopter_video_recorder_test";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

cv::Mat view(int width, int height, int value) {
  return cv::Mat(height, width, CV_8UC3, cv::Scalar(value, 255 - value, value / 2));
}

TEST(VideoRecorder, EveryViewIsInTheVideoResizedToTheFirstOnesSize) {
  for (int scale : {1, 2}) {
    const std::string path = tempPath("scale" + std::to_string(scale) + ".avi");
    {
      VideoRecorder recorder(path, 30, scale);
      for (int i = 0; i < 12; ++i)
        recorder.write(view(128, 96, 20 * i));
      recorder.write(view(160, 120, 7));  // another size: resized, not dropped
      recorder.close();
      EXPECT_EQ(recorder.framesWritten(), 13);
      recorder.close();  // idempotent
    }
    cv::VideoCapture capture(path);
    ASSERT_TRUE(capture.isOpened()) << path;
    int frames = 0;
    for (cv::Mat f; capture.read(f); ++frames) {
      EXPECT_EQ(f.cols, 128 / scale);
      EXPECT_EQ(f.rows, 96 / scale);
    }
    EXPECT_EQ(frames, 13);
  }
}

TEST(VideoRecorder, AFileThatCannotBeWrittenIsAnErrorNamingIt) {
  const std::string path = "/nonexistent-folder/run.avi";
  VideoRecorder recorder(path, 30, 1);
  EXPECT_THROW(
      {
        recorder.write(view(64, 48, 1));
        recorder.write(view(64, 48, 2));
        recorder.close();
      },
      Error);
  EXPECT_THROW(VideoRecorder(path, 30, 0), Error);
}

}  // namespace
}  // namespace horopter::cli
