// Chessboard corners with sub-pixel refinement, for every stereo pair.
#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "horopter/core/error.hpp"
#include "horopter/vision/calibration.hpp"

namespace horopter {

namespace {

std::string sizeText(cv::Size s) {
  return std::to_string(s.width) + "x" + std::to_string(s.height);
}

cv::Mat toGrey(const cv::Mat& image) {
  if (image.type() == CV_8UC1) return image;
  cv::Mat grey;
  if (image.type() == CV_8UC3) {
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  } else if (image.type() == CV_8UC4) {
    cv::cvtColor(image, grey, cv::COLOR_BGRA2GRAY);
  } else {
    throw Error("calibration images must be 8-bit grey or colour");
  }
  return grey;
}

}  // namespace

cv::Size parseBoardSize(const std::string& text) {
  // COLSxROWS: digits, 'x', digits, nothing else (no std::regex: GCC 12 warns
  // inside it under the sanitizers).
  const std::size_t x = text.find('x');
  const auto digits = [](const std::string& part) {
    return !part.empty() && part.size() <= 3 &&
           part.find_first_not_of("0123456789") == std::string::npos;
  };
  if (x == std::string::npos || !digits(text.substr(0, x)) || !digits(text.substr(x + 1)))
    throw Error("board size must be COLSxROWS of inner corners, e.g. 9x6, got '" + text + "'");
  const cv::Size s(std::stoi(text.substr(0, x)), std::stoi(text.substr(x + 1)));
  if (s.width < 2 || s.height < 2)
    throw Error("a board needs at least 2x2 inner corners, got " + text);
  if (s.width == s.height)
    throw Error("a square board (" + text +
                ") is ambiguous under rotation: use one with different corner counts, e.g. 9x6");
  return s;
}

std::vector<cv::Point2f> findBoardCorners(const cv::Mat& image, cv::Size innerCorners) {
  if (image.empty()) throw Error("cannot look for a board in an empty image");
  const cv::Mat grey = toGrey(image);
  std::vector<cv::Point2f> corners;
  const int flags = cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE;
  if (!cv::findChessboardCorners(grey, innerCorners, corners, flags)) return {};
  cv::cornerSubPix(grey, corners, cv::Size(11, 11), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 30, 0.01));
  return corners;
}

BoardDetections detectBoards(const std::vector<StereoImagePair>& pairs, cv::Size innerCorners,
                             const ProgressFn& progress) {
  BoardDetections out;
  const std::string board = sizeText(innerCorners);
  // The calibration's image size: the one most pairs have (a stray image of
  // another camera or resolution must not decide it).
  std::map<std::pair<int, int>, int> sizes;
  for (const StereoImagePair& p : pairs)
    if (!p.left.empty() && p.left.size() == p.right.size()) ++sizes[{p.left.cols, p.left.rows}];
  int most = 0;
  for (const auto& [size, count] : sizes) {
    if (count > most) {
      most = count;
      out.imageSize = cv::Size(size.first, size.second);
    }
  }
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const StereoImagePair& p = pairs[i];
    const std::string tag =
        "view " + std::to_string(i + 1) + "/" + std::to_string(pairs.size()) + " " + p.name + ": ";
    std::string why;
    if (p.left.empty() || p.right.empty()) {
      why = "an image is empty";
    } else if (p.left.size() != p.right.size()) {
      why = "left is " + sizeText(p.left.size()) + " but right is " + sizeText(p.right.size());
    } else if (p.left.size() != out.imageSize) {
      why = "it is " + sizeText(p.left.size()) + ", not the " + sizeText(out.imageSize) +
            " of most views";
    }
    BoardView view{p.name, {}, {}};
    if (why.empty()) {
      view.left = findBoardCorners(p.left, innerCorners);
      view.right = findBoardCorners(p.right, innerCorners);
      if (view.left.empty() || view.right.empty()) {
        why = "no " + board + " board in " +
              (view.left.empty() && view.right.empty() ? "either image"
               : view.left.empty()                     ? "the left image"
                                                       : "the right image");
      }
    }
    if (!why.empty()) {
      out.skipped.push_back(p.name + ": " + why);
      if (progress) progress(tag + "skipped, " + why);
      continue;
    }
    if (progress) progress(tag + std::to_string(view.left.size()) + " corners in both images");
    out.views.push_back(std::move(view));
  }
  return out;
}

}  // namespace horopter
