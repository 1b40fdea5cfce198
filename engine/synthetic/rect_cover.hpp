// Disjoint rectangles that cover a set of rectangles: overlapping ones are
// replaced by their bounding rectangle until none overlap. The incremental
// renderer draws each once, so a pixel is never drawn twice, and two parts
// that changed far apart (a waving hand, the other person) do not make it
// redraw everything between them.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

namespace horopter::synth {

inline std::vector<cv::Rect> disjointCover(std::vector<cv::Rect> rects) {
  std::vector<cv::Rect> out;
  for (const cv::Rect& r : rects)
    if (!r.empty()) out.push_back(r);
  for (bool merged = true; merged;) {
    merged = false;
    for (std::size_t i = 0; i < out.size() && !merged; ++i)
      for (std::size_t j = i + 1; j < out.size(); ++j)
        if (!(out[i] & out[j]).empty()) {
          out[i] |= out[j];
          out.erase(out.begin() + static_cast<std::ptrdiff_t>(j));
          merged = true;
          break;
        }
  }
  return out;
}

}  // namespace horopter::synth
