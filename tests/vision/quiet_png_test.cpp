// Reading PNG files without their iCCP chunk (libpng's "known incorrect sRGB
// profile" warning): the same pixels, every other byte kept.
#include <cstdint>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "io/image_files.hpp"
#include "io/quiet_png.hpp"

namespace horopter::test {
namespace {

std::vector<std::uint8_t> smallPng() {
  cv::Mat image(4, 5, CV_8UC3);
  cv::randu(image, 0, 255);
  std::vector<std::uint8_t> bytes;
  EXPECT_TRUE(cv::imencode(".png", image, bytes));
  return bytes;
}

// A PNG with a made-up iCCP chunk after IHDR (8-byte signature, IHDR is
// 4 + 4 + 13 + 4 bytes).
std::vector<std::uint8_t> withIccp(const std::vector<std::uint8_t>& png) {
  const std::uint8_t chunk[] = {0, 0, 0, 3, 'i', 'C', 'C', 'P', 'a', 'b', 'c', 1, 2, 3, 4};
  std::vector<std::uint8_t> out;
  out.reserve(png.size() + sizeof chunk);
  for (std::size_t i = 0; i < png.size(); ++i) {
    if (i == 33)
      for (std::uint8_t b : chunk)
        out.push_back(b);
    out.push_back(png[i]);
  }
  return out;
}

TEST(QuietPng, DropsExactlyTheIccpChunk) {
  const std::vector<std::uint8_t> png = smallPng();
  EXPECT_EQ(withoutIccpChunks(withIccp(png)), png);
  EXPECT_EQ(withoutIccpChunks(png), png);
  // Not a PNG, or a truncated one: unchanged, for the decoder to judge.
  const std::vector<std::uint8_t> text = {'n', 'o', 't', ' ', 'a', ' ', 'P', 'N', 'G'};
  EXPECT_EQ(withoutIccpChunks(text), text);
  std::vector<std::uint8_t> cut = withIccp(png);
  cut.resize(40);
  EXPECT_EQ(withoutIccpChunks(cut), cut);
}

// The scene's texture files decode to the same pixels as through cv::imread.
TEST(QuietPng, SamePixelsAsImread) {
  const std::vector<std::string> files = {
      "/usr/lib/python3/dist-packages/skimage/data/astronaut.png",
      "/usr/lib/python3/dist-packages/skimage/data/chelsea.png",
      "/usr/share/doc/opencv-doc/examples/data/orange.jpg"};
  int seen = 0;
  for (const std::string& f : files) {
    if (!std::filesystem::exists(f)) continue;
    ++seen;
    const cv::Mat theirs = cv::imread(f, cv::IMREAD_COLOR);
    const cv::Mat ours = readImage(f, cv::IMREAD_COLOR);
    ASSERT_FALSE(ours.empty()) << f;
    ASSERT_EQ(ours.size(), theirs.size()) << f;
    ASSERT_EQ(ours.type(), theirs.type()) << f;
    EXPECT_EQ(cv::norm(ours, theirs, cv::NORM_INF), 0) << f;
  }
  if (seen == 0) GTEST_SKIP() << "no texture files here (python3-skimage, opencv-doc)";
  EXPECT_TRUE(readImage("/no/such/file.png", cv::IMREAD_COLOR).empty());
}

}  // namespace
}  // namespace horopter::test
