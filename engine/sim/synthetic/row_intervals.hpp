// A set of pixels as [x0, x1) intervals per row: where the incremental
// renderer draws again (the pixels the changed parts of the people covered
// or now cover), tighter than their rectangles.
#pragma once

#include <algorithm>
#include <vector>

namespace horopter::synth {

struct Interval {
  int x0 = 0, x1 = 0;  // [x0, x1)
};

class RowIntervals {
 public:
  // Empties the set for an image `height` rows high (keeps the capacity).
  void reset(int height) {
    rows_.resize(static_cast<std::size_t>(height));
    for (auto& r : rows_)
      r.clear();
  }
  int height() const { return static_cast<int>(rows_.size()); }
  void add(int y, int x0, int x1) {
    if (x1 > x0) rows_[static_cast<std::size_t>(y)].push_back({x0, x1});
  }
  // Sorts each row and merges intervals that overlap or touch, so that every
  // pixel is in one interval at most.
  void merge() {
    for (auto& r : rows_) {
      if (r.size() < 2) continue;
      std::sort(r.begin(), r.end(),
                [](const Interval& a, const Interval& b) { return a.x0 < b.x0; });
      std::size_t n = 0;
      for (std::size_t i = 1; i < r.size(); ++i) {
        if (r[i].x0 <= r[n].x1)
          r[n].x1 = std::max(r[n].x1, r[i].x1);
        else
          r[++n] = r[i];
      }
      r.resize(n + 1);
    }
  }
  const std::vector<Interval>& row(int y) const { return rows_[static_cast<std::size_t>(y)]; }

 private:
  std::vector<std::vector<Interval>> rows_;
};

}  // namespace horopter::synth
