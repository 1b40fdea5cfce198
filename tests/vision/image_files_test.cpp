// Image files: sizes read from the header before anything is decoded, and
// files too large refused before their pixels are allocated.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "io/image_files.hpp"
#include "test_support.hpp"

namespace horopter {
namespace {

namespace fs = std::filesystem;

std::vector<std::uint8_t> encoded(const std::string& ext, cv::Size size, int type) {
  cv::Mat image(size, type);
  cv::randu(image, 0, 255);
  std::vector<std::uint8_t> bytes;
  EXPECT_TRUE(cv::imencode(ext, image, bytes)) << ext;
  return bytes;
}

TEST(ImageFiles, HeaderSizeOfEveryFormatOpenCvWrites) {
  for (const std::string ext : {".png", ".jpg", ".bmp", ".pgm", ".ppm"}) {
    const int type = ext == ".pgm" ? CV_8UC1 : CV_8UC3;
    for (const cv::Size size : {cv::Size(1, 1), cv::Size(37, 5), cv::Size(640, 481)}) {
      const auto header = imageHeaderSize(encoded(ext, size, type));
      ASSERT_TRUE(header.has_value()) << ext << " " << size;
      EXPECT_EQ(*header, size) << ext;
    }
  }
}

TEST(ImageFiles, HeaderSizeSkipsJpegSegmentsBeforeTheFrame) {
  // An EXIF-like APP1 segment of 3 000 bytes between SOI and the frame.
  const std::vector<std::uint8_t> jpeg = encoded(".jpg", {23, 17}, CV_8UC3);
  const std::size_t length = 3000;
  std::vector<std::uint8_t> withApp1 = {jpeg[0],
                                        jpeg[1],
                                        0xFF,
                                        0xE1,
                                        static_cast<std::uint8_t>(length >> 8),
                                        static_cast<std::uint8_t>(length & 0xFF)};
  withApp1.resize(withApp1.size() + length - 2, 0x00);
  withApp1.insert(withApp1.end(), jpeg.begin() + 2, jpeg.end());
  EXPECT_EQ(imageHeaderSize(withApp1), cv::Size(23, 17));
}

TEST(ImageFiles, HeaderSizeOfOtherOrCutBytesIsUnknown) {
  const std::vector<std::uint8_t> png = encoded(".png", {8, 8}, CV_8UC1);
  EXPECT_FALSE(imageHeaderSize(std::vector<std::uint8_t>(png.begin(), png.begin() + 20)));
  const std::vector<std::uint8_t> jpeg = encoded(".jpg", {8, 8}, CV_8UC1);
  EXPECT_FALSE(imageHeaderSize(std::vector<std::uint8_t>(jpeg.begin(), jpeg.begin() + 6)));
  const std::string text = "not an image";
  EXPECT_FALSE(imageHeaderSize(std::vector<std::uint8_t>(text.begin(), text.end())));
  EXPECT_FALSE(imageHeaderSize(std::vector<std::uint8_t>{}));
}

// A PNG header saying 20000x20000 on a file of a few bytes: OpenCV alone
// allocates the whole image (1.2 GB in colour) before finding the data missing.
TEST(ImageFiles, AHugeImageIsRefusedBeforeDecoding) {
  std::vector<std::uint8_t> png = encoded(".png", {8, 8}, CV_8UC1);
  const std::uint32_t side = 20000;
  for (int at : {16, 20})
    for (int i = 0; i < 4; ++i)
      png[static_cast<std::size_t>(at + i)] = static_cast<std::uint8_t>(side >> (24 - 8 * i));
  const fs::path path = fs::path(::testing::TempDir()) / "horopter_huge.png";
  {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
    ASSERT_TRUE(out.good());
  }
  const std::string message = test::errorOf([&] { readImage(path.string(), cv::IMREAD_COLOR); });
  EXPECT_NE(message.find("20000x20000"), std::string::npos) << message;
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
}

TEST(ImageFiles, ReadImageDecodesWhatImreadDecodes) {
  const fs::path dir = fs::path(::testing::TempDir());
  cv::Mat image(31, 45, CV_8UC3);
  cv::randu(image, 0, 255);
  for (const std::string ext : {".png", ".bmp", ".ppm"}) {
    const fs::path path = dir / ("horopter_read" + ext);
    ASSERT_TRUE(cv::imwrite(path.string(), image));
    const cv::Mat ours = readImage(path.string(), cv::IMREAD_COLOR);
    ASSERT_EQ(ours.size(), image.size()) << ext;
    EXPECT_EQ(cv::norm(ours, cv::imread(path.string(), cv::IMREAD_COLOR), cv::NORM_INF), 0) << ext;
  }
  EXPECT_TRUE(readImage((dir / "horopter_no_such.png").string(), cv::IMREAD_COLOR).empty());
}

}  // namespace
}  // namespace horopter
