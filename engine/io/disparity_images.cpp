#include "disparity_images.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>
#include <vector>
#include "file_output.hpp"
#include "horopter/core/error.hpp"
#include "horopter/vision/opencv.hpp"
#include "io/image_files.hpp"

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

namespace {

// OpenCV's JET colour map of the levels 0..255 (low = blue, high = red), made
// once: cv::applyColorMap builds its table on every call.
const cv::Mat& jetColours() {
  static const cv::Mat colours = [] {
    cv::Mat ramp(1, 256, CV_8UC1), jet;
    for (int i = 0; i < 256; ++i)
      ramp.at<std::uint8_t>(0, i) = static_cast<std::uint8_t>(i);
    cv::applyColorMap(ramp, jet, cv::COLORMAP_JET);
    return jet;
  }();
  return colours;
}

}  // namespace

cv::Mat colorizeDisparity(const ConstImageView& disparity, const StereoParams& params) {
  checkView(disparity, PixelType::S16C1, "disparity");
  cv::Mat out(disparity.height, disparity.width, CV_8UC3);
  colorizeDisparityInto(disparity, params, out);
  return out;
}

void colorizeDisparityInto(const ConstImageView& disparity, const StereoParams& params,
                           cv::Mat& out) {
  checkView(disparity, PixelType::S16C1, "disparity");
  if (out.type() != CV_8UC3 || out.rows != disparity.height || out.cols != disparity.width)
    throw Error("the disparity's colour view must be a BGR image of the disparity's size");
  const std::int16_t invalid = invalidDisparity(params);
  const int lo = params.minDisparity * kDisparityScale;
  const int hi = (params.minDisparity + params.numDisparities) * kDisparityScale;
  // One colour per disparity in [lo, hi] (those outside take the ends', as
  // the level saturates): a table lookup per pixel, where a division and
  // the colour map per pixel cost half the annotated view's time. Entry 0
  // is the invalid disparity's black. Each entry is a colour's 3 bytes in a
  // 4-byte word, stored whole: its 4th byte lands on the next pixel, which
  // overwrites it (the row's last pixel copies 3 bytes, so nothing past the
  // row is touched): 4 % fewer instructions than Vec3b assignments (callgrind).
  const cv::Mat& jet = jetColours();
  std::vector<std::uint32_t> colourOf(static_cast<std::size_t>(hi - lo + 2), 0);
  for (int v = lo; v <= hi; ++v) {
    const cv::Vec3b colour = jet.at<cv::Vec3b>(
        0, cv::saturate_cast<std::uint8_t>(255.0 * (v - lo) / static_cast<double>(hi - lo)));
    std::memcpy(&colourOf[static_cast<std::size_t>(v - lo + 1)], colour.val, 3);
  }
  auto entryOf = [&](std::int16_t d) {
    return d == invalid ? std::size_t{0}
                        : static_cast<std::size_t>(std::clamp<int>(d, lo, hi) - lo + 1);
  };
  if (disparity.width < 1) return;
  const int last = disparity.width - 1;
  for (int y = 0; y < disparity.height; ++y) {
    const auto* d = disparity.row<std::int16_t>(y);
    std::uint8_t* o = out.ptr<std::uint8_t>(y);
    for (int x = 0; x < last; ++x)
      std::memcpy(o + 3 * static_cast<std::size_t>(x), &colourOf[entryOf(d[x])], 4);
    std::memcpy(o + 3 * static_cast<std::size_t>(last), &colourOf[entryOf(d[last])], 3);
  }
}

namespace {

constexpr int kScaleFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kScaleFontScale = 0.4;
constexpr int kScaleBarHeight = 8, kScaleMargin = 6, kScaleTextHeight = 14;

}  // namespace

cv::Rect disparityScaleRect(cv::Size view, int shrink) {
  // A third of the width, at most 240 px; nothing below 60 px of bar (each
  // divided by shrink on a view drawn at 1/shrink of its size).
  shrink = std::max(1, shrink);
  const int barWidth = std::min(240 / shrink, view.width / 3);
  const int height = (kScaleBarHeight + kScaleTextHeight + 2 * kScaleMargin) / shrink;
  const int width = barWidth + 2 * (kScaleMargin / shrink);
  if (barWidth < 60 / shrink || view.height < 3 * height) return {};
  return {view.width - width, view.height - height, width, height};
}

cv::Rect drawDisparityScale(cv::Mat& view, const StereoParams& params, int shrink) {
  shrink = std::max(1, shrink);
  const cv::Rect area = disparityScaleRect(view.size(), shrink);
  if (area.empty() || view.type() != CV_8UC3) return {};
  cv::Mat under = view(area);
  under.convertTo(under, -1, 0.3);  // a dark backing, readable over any colour
  const int margin = kScaleMargin / shrink, barHeight = kScaleBarHeight / shrink;
  const int textHeight = kScaleTextHeight / shrink;
  const double fontScale = kScaleFontScale / shrink;
  const int barWidth = area.width - 2 * margin;
  cv::Mat bar(1, barWidth, CV_8UC3);  // the map's own colours
  for (int x = 0; x < barWidth; ++x)
    bar.at<cv::Vec3b>(0, x) =
        jetColours().at<cv::Vec3b>(0, cv::saturate_cast<std::uint8_t>(255.0 * x / (barWidth - 1)));
  const cv::Rect barArea(area.x + margin, area.y + margin, barWidth, barHeight);
  cv::Mat barView = view(barArea);  // resize writes into it in place: same size and type
  cv::resize(bar, barView, barArea.size(), 0, 0, cv::INTER_NEAREST);
  const int lo = params.minDisparity, hi = params.minDisparity + params.numDisparities;
  const std::string loText = std::to_string(lo) + " px", hiText = std::to_string(hi) + " px";
  int baseline = 0;
  const int hiWidth = cv::getTextSize(hiText, kScaleFont, fontScale, 1, &baseline).width;
  const int textY = barArea.y + barHeight + textHeight - 2 / shrink;
  const cv::Scalar white(255, 255, 255);
  cv::putText(view, loText, {barArea.x, textY}, kScaleFont, fontScale, white, 1, cv::LINE_AA);
  cv::putText(view, hiText, {barArea.x + barWidth - hiWidth, textY}, kScaleFont, fontScale, white,
              1, cv::LINE_AA);
  return area;
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

cv::Mat encodeDisparity16(const ConstImageView& disparity, std::int16_t invalid) {
  checkView(disparity, PixelType::S16C1, "disparity");
  cv::Mat out(disparity.height, disparity.width, CV_16UC1);
  for (int y = 0; y < disparity.height; ++y) {
    const auto* d = disparity.row<std::int16_t>(y);
    auto* o = out.ptr<std::uint16_t>(y);
    for (int x = 0; x < disparity.width; ++x) {
      const int v = d[x] == std::numeric_limits<std::int16_t>::min() ? d[x] + 1 : d[x];
      o[x] = d[x] == invalid ? 0 : static_cast<std::uint16_t>(v + kDisparity16Offset);
    }
  }
  return out;
}

void writeDisparity16Png(const std::string& path, const ConstImageView& disparity,
                         std::int16_t invalid) {
  writeImageFile(path, encodeDisparity16(disparity, invalid), "disparity image");
}

cv::Mat readDisparity16Png(const std::string& path, std::int16_t invalid) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error("cannot read the disparity image '" + path + "': no such file");
  const cv::Mat raw = readImage(path, cv::IMREAD_UNCHANGED);
  if (raw.empty())
    throw Error("cannot read the disparity image '" + path + "': it could not be decoded");
  if (raw.type() != CV_16UC1)
    throw Error("the disparity image '" + path + "' is " + cv::typeToString(raw.type()) +
                ", not 16-bit single-channel (disparity16.png: d16 + 32768, 0 = invalid)");
  cv::Mat out(raw.size(), CV_16SC1);
  for (int y = 0; y < raw.rows; ++y) {
    const auto* r = raw.ptr<std::uint16_t>(y);
    auto* o = out.ptr<std::int16_t>(y);
    for (int x = 0; x < raw.cols; ++x)
      o[x] = r[x] == 0 ? invalid : static_cast<std::int16_t>(int{r[x]} - kDisparity16Offset);
  }
  return out;
}

namespace {

// PFM stores float32 rows bottom to top, in the byte order the scale's sign
// names (negative = little-endian).
std::uint32_t swapBytes(std::uint32_t v) {
  return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}

}  // namespace

void writePfm(const std::string& path, const cv::Mat& image) {
  if (image.type() != CV_32FC1)
    throw Error("cannot write the PFM file '" + path + "': expected CV_32FC1, got " +
                cv::typeToString(image.type()));
  std::string bytes =
      "Pf\n" + std::to_string(image.cols) + " " + std::to_string(image.rows) + "\n-1.0\n";
  const std::size_t header = bytes.size();
  const std::size_t rowBytes = static_cast<std::size_t>(image.cols) * sizeof(float);
  bytes.resize(header + rowBytes * static_cast<std::size_t>(image.rows));
  for (int y = 0; y < image.rows; ++y) {
    char* dst = bytes.data() + header + rowBytes * static_cast<std::size_t>(image.rows - 1 - y);
    const auto* src = image.ptr<float>(y);
    for (int x = 0; x < image.cols; ++x) {
      std::uint32_t v = std::bit_cast<std::uint32_t>(src[x]);
      if constexpr (std::endian::native == std::endian::big) v = swapBytes(v);
      std::memcpy(dst + x * sizeof(float), &v, sizeof v);
    }
  }
  detail::writeFile(path, bytes, "PFM file");
}

void writeDisparityPfm(const std::string& path, const ConstImageView& disparity,
                       std::int16_t invalid) {
  checkView(disparity, PixelType::S16C1, "disparity");
  cv::Mat px(disparity.height, disparity.width, CV_32FC1);
  for (int y = 0; y < disparity.height; ++y) {
    const auto* d = disparity.row<std::int16_t>(y);
    auto* o = px.ptr<float>(y);
    for (int x = 0; x < disparity.width; ++x)
      o[x] = d[x] == invalid ? std::numeric_limits<float>::infinity()
                             : static_cast<float>(d[x]) / kDisparityScale;
  }
  writePfm(path, px);
}

bool isPfmFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[2] = {0, 0};
  in.read(magic, 2);
  return in && magic[0] == 'P' && (magic[1] == 'f' || magic[1] == 'F');
}

cv::Mat readPfm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read the PFM file '" + path + "': no such file or not readable");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto bad = [&](const std::string& why) {
    return Error("cannot read the PFM file '" + path + "': " + why);
  };
  // Header: "Pf" or "PF", width, height, scale, each separated by white
  // space, then exactly one white-space character before the data.
  std::size_t pos = 0;
  std::string tokens[4];
  for (std::string& token : tokens) {
    while (pos < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[pos])))
      ++pos;
    while (pos < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[pos])))
      token += bytes[pos++];
    if (token.empty() || pos >= bytes.size()) throw bad("the header is incomplete");
  }
  ++pos;  // the single white-space character that ends the header
  if (tokens[0] != "Pf" && tokens[0] != "PF")
    throw bad("it does not start with Pf or PF (not a PFM file)");
  const int channels = tokens[0] == "PF" ? 3 : 1;
  int width = 0, height = 0;
  double scale = 0;
  try {
    std::size_t used = 0;
    width = std::stoi(tokens[1], &used);
    if (used != tokens[1].size()) throw std::invalid_argument("width");
    height = std::stoi(tokens[2], &used);
    if (used != tokens[2].size()) throw std::invalid_argument("height");
    scale = std::stod(tokens[3], &used);
    if (used != tokens[3].size()) throw std::invalid_argument("scale");
  } catch (const std::exception&) {
    throw bad("the header's width, height or scale is not a number");
  }
  if (width <= 0 || height <= 0 || width > (1 << 16) || height > (1 << 16) || scale == 0 ||
      !std::isfinite(scale))
    throw bad("the header gives " + tokens[1] + " x " + tokens[2] + ", scale " + tokens[3]);
  const bool littleEndian = scale < 0;
  const std::size_t rowValues = static_cast<std::size_t>(width) * channels;
  const std::size_t need = rowValues * sizeof(float) * static_cast<std::size_t>(height);
  if (bytes.size() - pos < need)
    throw bad("it holds " + std::to_string(bytes.size() - pos) + " bytes of data, " +
              std::to_string(width) + " x " + std::to_string(height) + " needs " +
              std::to_string(need));
  const bool swap = littleEndian != (std::endian::native == std::endian::little);
  cv::Mat out(height, width, CV_32FC1);
  for (int y = 0; y < height; ++y) {
    const char* src =
        bytes.data() + pos + rowValues * sizeof(float) * static_cast<std::size_t>(height - 1 - y);
    auto* o = out.ptr<float>(y);
    for (int x = 0; x < width; ++x) {
      std::uint32_t v = 0;
      std::memcpy(&v, src + static_cast<std::size_t>(x) * channels * sizeof(float), sizeof v);
      o[x] = std::bit_cast<float>(swap ? swapBytes(v) : v);
    }
  }
  return out;
}

void writeFrontendOutputs(const std::string& dir, const StereoFrontend& frontend) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error("could not create output folder '" + dir + "': " + ec.message());
  const auto& p = frontend.stereoParams();
  const auto disparity = frontend.disparity().view();
  writeDisparityPng(dir + "/disparity.png", disparity, invalidDisparity(p));
  writeDisparity16Png(dir + "/disparity16.png", disparity, invalidDisparity(p));
  writeDisparityPfm(dir + "/disparity.pfm", disparity, invalidDisparity(p));
  cv::Mat colour = colorizeDisparity(disparity, p);
  drawDisparityScale(colour, p);
  writeImageFile(dir + "/disparity_color.png", colour, "image");
  if (!frontend.mask().empty()) writeImageFile(dir + "/mask.png", matOf(frontend.mask()), "image");
  if (!frontend.segmented().empty())
    writeImageFile(dir + "/segmented.png", matOf(frontend.segmented()), "image");
}

}  // namespace horopter
