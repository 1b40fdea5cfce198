// File-based sources: a folder of left/right images and a pair of videos.
#include "capture/file_sources.hpp"

#include <algorithm>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "horopter/core/error.hpp"

namespace horopter::capture {

namespace fs = std::filesystem;

namespace {

bool isImage(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".pgm" ||
         ext == ".ppm" || ext == ".tif" || ext == ".tiff";
}

// Image files in `dir` whose name starts with `prefix` (all when empty), sorted.
std::vector<fs::path> imagesIn(const fs::path& dir, const std::string& prefix) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (!entry.is_regular_file() || !isImage(entry.path())) continue;
    if (entry.path().filename().string().rfind(prefix, 0) == 0) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

cv::Mat readImage(const fs::path& path) {
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_COLOR);
  if (image.empty())
    throw Error("cannot read image '" + path.string() + "': not an image or unreadable");
  return image;
}

void checkPair(const cv::Mat& left, const cv::Mat& right, const std::string& what) {
  if (left.size() != right.size())
    throw Error(what + ": left is " + std::to_string(left.cols) + "x" + std::to_string(left.rows) +
                " but right is " + std::to_string(right.cols) + "x" + std::to_string(right.rows) +
                ": both views of a pair must have one size");
}

}  // namespace

DirectorySource::DirectorySource(const std::string& dir) : dir_(dir) {
  const fs::path root(dir);
  if (!fs::is_directory(root))
    throw Error("image folder '" + dir + "' does not exist (dir:PATH needs a folder)");
  if (fs::is_directory(root / "left") && fs::is_directory(root / "right")) {
    left_ = imagesIn(root / "left", "");
    right_ = imagesIn(root / "right", "");
  } else {
    left_ = imagesIn(root, "left");
    right_ = imagesIn(root, "right");
  }
  if (left_.empty())
    throw Error("no stereo images in '" + dir +
                "': expected left*.png/right*.png (or .jpg) or left/ and right/ subfolders");
  if (left_.size() != right_.size())
    throw Error("'" + dir + "' has " + std::to_string(left_.size()) + " left and " +
                std::to_string(right_.size()) + " right images: each left needs its right");
}

bool DirectorySource::next(StereoFrame& frame) {
  if (next_ >= left_.size()) return false;
  frame.left = readImage(left_[next_]);
  frame.right = readImage(right_[next_]);
  checkPair(frame.left, frame.right, left_[next_].filename().string());
  ++next_;
  return true;
}

VideoPairSource::VideoPairSource(const std::string& leftPath, const std::string& rightPath)
    : leftPath_(leftPath), rightPath_(rightPath) {
  for (const auto& [path, capture] :
       {std::pair{&leftPath_, &left_}, std::pair{&rightPath_, &right_}}) {
    if (!fs::is_regular_file(*path)) throw Error("video file '" + *path + "' does not exist");
    if (!capture->open(*path))
      throw Error("cannot open video '" + *path + "': not a video OpenCV can decode");
  }
}

bool VideoPairSource::next(StereoFrame& frame) {
  const bool gotLeft = left_.read(frame.left);
  const bool gotRight = right_.read(frame.right);
  if (!gotLeft && !gotRight) return false;
  if (gotLeft != gotRight)
    throw Error("'" + (gotLeft ? rightPath_ : leftPath_) + "' ended at frame " +
                std::to_string(frames_) +
                " before the other video: the pair must be the same length");
  checkPair(frame.left, frame.right, "video frame " + std::to_string(frames_));
  ++frames_;
  return true;
}

}  // namespace horopter::capture
