#include "disparity_images.hpp"

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <vector>
#include "file_output.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/opencv.hpp"

namespace horopter {

void writeImageFile(const std::string& path, const cv::Mat& image, const std::string& what) {
  // Encoded in memory, then written checked: cv::imwrite does not report a
  // write that fails in its buffers (a full disk).
  const std::string extension = std::filesystem::path(path).extension().string();
  std::vector<std::uint8_t> bytes;
  bool ok = false;
  try {
    ok = !extension.empty() && cv::imencode(extension, image, bytes);
  } catch (const cv::Exception& e) {
    throw Error("cannot write the " + what + " '" + path + "': " + e.what());
  }
  if (!ok)
    throw Error("cannot write the " + what + " '" + path +
                "': OpenCV cannot encode it (use a name ending in .png or .jpg)");
  detail::writeFile(
      path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), what);
}

cv::Mat colorizeDisparity(const ConstImageView& disparity, const StereoParams& params) {
  const std::int16_t invalid = invalidDisparity(params);
  const double lo = params.minDisparity * kDisparityScale;
  const double hi = (params.minDisparity + params.numDisparities) * kDisparityScale;
  cv::Mat level(disparity.height, disparity.width, CV_8UC1);
  cv::Mat valid(disparity.height, disparity.width, CV_8UC1);
  for (int y = 0; y < disparity.height; ++y) {
    const auto* d = disparity.row<std::int16_t>(y);
    for (int x = 0; x < disparity.width; ++x) {
      valid.at<std::uint8_t>(y, x) = d[x] != invalid ? 255 : 0;
      level.at<std::uint8_t>(y, x) =
          cv::saturate_cast<std::uint8_t>(255.0 * (d[x] - lo) / (hi - lo));
    }
  }
  cv::Mat colour;
  cv::applyColorMap(level, colour, cv::COLORMAP_JET);  // low = blue, high = red
  cv::Mat out = cv::Mat::zeros(colour.size(), colour.type());
  colour.copyTo(out, valid);
  return out;
}

void writeDisparityPng(const std::string& path, const ConstImageView& disparity,
                       std::int16_t invalid) {
  cv::Mat out(disparity.height, disparity.width, CV_16UC1);
  for (int y = 0; y < disparity.height; ++y) {
    const auto* d = disparity.row<std::int16_t>(y);
    auto* o = out.ptr<std::uint16_t>(y);
    for (int x = 0; x < disparity.width; ++x)
      o[x] = (d[x] == invalid || d[x] <= 0) ? 0 : static_cast<std::uint16_t>(d[x]);
  }
  writeImageFile(path, out, "disparity image");
}

void writeFrontendOutputs(const std::string& dir, const StereoFrontend& frontend) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error("could not create output folder '" + dir + "': " + ec.message());
  const auto& p = frontend.stereoParams();
  const auto disparity = frontend.disparity().view();
  writeDisparityPng(dir + "/disparity.png", disparity, invalidDisparity(p));
  writeImageFile(dir + "/disparity_color.png", colorizeDisparity(disparity, p), "image");
  if (!frontend.mask().empty()) writeImageFile(dir + "/mask.png", matOf(frontend.mask()), "image");
  if (!frontend.segmented().empty())
    writeImageFile(dir + "/segmented.png", matOf(frontend.segmented()), "image");
}

}  // namespace horopter
