// File-based sources: a folder of left/right images and a pair of videos.
#include "capture/file_sources.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <string_view>
#include <tuple>

#include "horopter/core/error.hpp"
#include "io/image_files.hpp"

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

// Digit runs compare as numbers, so "left2" comes before "left10".
bool naturalLess(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) &&
        std::isdigit(static_cast<unsigned char>(b[j]))) {
      const std::size_t i0 = i, j0 = j;
      while (i < a.size() && std::isdigit(static_cast<unsigned char>(a[i])))
        ++i;
      while (j < b.size() && std::isdigit(static_cast<unsigned char>(b[j])))
        ++j;
      // Without leading zeros, a longer run is a larger number.
      std::string_view x(a.data() + i0, i - i0), y(b.data() + j0, j - j0);
      x.remove_prefix(std::min(x.find_first_not_of('0'), x.size()));
      y.remove_prefix(std::min(y.find_first_not_of('0'), y.size()));
      if (x.size() != y.size()) return x.size() < y.size();
      if (x != y) return x < y;
      continue;
    }
    if (a[i] != b[j]) return a[i] < b[j];
    ++i;
    ++j;
  }
  return a.size() - i < b.size() - j;
}

// Image files in `dir` whose name starts with `prefix` (all when empty), by
// the name that pairs them: the stem less the prefix ("left_007.png" and
// "right_007.jpg" are both "_007").
std::map<std::string, fs::path> imagesIn(const fs::path& dir, const std::string& prefix) {
  std::map<std::string, fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const fs::path& p = entry.path();
    if (!entry.is_regular_file() || !isImage(p)) continue;
    const std::string stem = p.stem().string();
    if (stem.rfind(prefix, 0) != 0) continue;
    const auto [at, added] = files.emplace(stem.substr(prefix.size()), p);
    if (!added)
      throw Error("'" + at->second.string() + "' and '" + p.string() +
                  "' have one name: keep one image per name and view");
  }
  return files;
}

// The left and right images paired by name, in natural order of the names;
// an image without its partner is an error that names it.
void pairByName(const std::map<std::string, fs::path>& left,
                const std::map<std::string, fs::path>& right, const std::string& dir,
                std::vector<fs::path>& leftOut, std::vector<fs::path>& rightOut) {
  for (const auto& [side, own, other] :
       {std::tuple{"left", &left, &right}, std::tuple{"right", &right, &left}})
    for (const auto& [name, path] : *own)
      if (!other->contains(name))
        throw Error("'" + dir + "': " + side + " image '" + path.filename().string() + "' has no " +
                    (std::string(side) == "left" ? "right" : "left") +
                    " image of the same name; left and right images are paired by name "
                    "(left0007.png with right0007.png, or left/0007.png with right/0007.png)");
  std::vector<std::string> names;
  for (const auto& entry : left)
    names.push_back(entry.first);
  std::sort(names.begin(), names.end(), naturalLess);
  for (const std::string& name : names) {
    leftOut.push_back(left.at(name));
    rightOut.push_back(right.at(name));
  }
}

cv::Mat readFrameImage(const fs::path& path) {
  cv::Mat image = readImage(path.string(), cv::IMREAD_COLOR);
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
  const bool subfolders = fs::is_directory(root / "left") && fs::is_directory(root / "right");
  const auto left = subfolders ? imagesIn(root / "left", "") : imagesIn(root, "left");
  const auto right = subfolders ? imagesIn(root / "right", "") : imagesIn(root, "right");
  if (left.empty())
    throw Error("no stereo images in '" + dir +
                "': expected left*.png/right*.png (or .jpg) or left/ and right/ subfolders");
  if (left.size() != right.size())
    throw Error("'" + dir + "' has " + std::to_string(left.size()) + " left and " +
                std::to_string(right.size()) + " right images: each left needs its right");
  pairByName(left, right, dir, left_, right_);
}

bool DirectorySource::next(StereoFrame& frame) {
  if (next_ >= left_.size()) return false;
  frame.left = readFrameImage(left_[next_]);
  frame.right = readFrameImage(right_[next_]);
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
