// Scalar reference of SAD block matching: THE SPECIFICATION.
//
// Semantics
//   Inputs: left L and right R, U8C1, W x H (prefiltered or raw); texture T,
//   U8C1 (read only when textureThreshold > 0). r = blockSize / 2.
//   Disparities d = minDisparity .. maxD, maxD = minDisparity + numDisparities - 1.
//   A left pixel (x, y) matches the right pixel (x - d, y).
//
//   Region (matchRegion): rows y in [r, H - r); columns x in [x0, x1) with
//   x0 = max(r, r + maxD) and x1 = min(W - r, W - r + minDisparity), so every
//   window of every disparity lies inside both images. Outside the region the
//   disparity is invalid ((minDisparity - 1) * 16) and winnerRight is
//   minDisparity - 1.
//
//   Left band (params.leftBand = m > 0): the left view's columns left of the
//   region, x in [bx0, x0) with bx0 = max(r, r + minDisparity + m - 1), whose
//   windows fit in the right image for at least m disparities of the range,
//   are matched too, each over its own range d in [minDisparity, top(x)],
//   top(x) = x - r (the window's left edge at the right image's column 0).
//   Every rule below holds for a band pixel with top(x) in place of maxD:
//   winner, uniqueness, the guard, the sub-pixel fit mirrored at top(x), and
//   the right winner, whose candidates are the left pixels of the band and
//   the region with d <= top(xr + d). top(x) = maxD in the region; m = 0
//   (the default) or m > numDisparities leaves no band (bx0 = x0).
//
//   Cost: C(x, y, d) = sum over |i|, |j| <= r of |L(x+i, y+j) - R(x+i-d, y+j)|,
//   exact in int32 (at most 255 * 255^2 < 2^31).
//
//   Winner: b = the d of least cost; ties go to the smallest d.
//
//   Texture: if textureThreshold > 0 and the window sum of T around (x, y) is
//   < textureThreshold, the pixel is invalid.
//
//   Uniqueness: if uniquenessRatio > 0, let t = C(b) + C(b) * uniquenessRatio / 100
//   (integer division, 64-bit). The pixel is invalid if some d with |d - b| > 1
//   has C(d) <= t.
//
//   Sub-pixel (equiangular line fit, integers only): c0 = C(b),
//   cm = C(b - 1), cp = C(b + 1); at the ends of the range the missing side
//   mirrors the other one (cm = cp), which gives offset 0.
//     den = cm + cp - 2 c0 + |cm - cp|          (>= 0)
//     off = den > 0 ? (cm - cp) * 256 / den : 0 (64-bit, truncated toward 0;
//                                                |off| <= 128)
//     disparity = (b * 256 + off + 8) >> 4      (arithmetic shift: floor)
//   i.e. 1/16 px, rounded to nearest with halves up.
//
//   Guard below the range (matchBlocks with a BelowRangeGuard, step > 0;
//   zone-limited matching): the checked disparities are
//   g_k = minDisparity - k * step for k = 1 .. K, K = (minDisparity - lowest)
//   / step (none when lowest = minDisparity). g_k counts for pixel (x, y)
//   where its window lies inside the right image, x - g_k + r <= W - 1 (for
//   g_k >= 0 everywhere in the region; the left edge always holds). With
//   G = the least C(x, y, g_k) over the g_k that count (none: no check), the
//   pixel is invalid if G <= t, t the uniqueness limit above, or C(b) when
//   uniquenessRatio is 0: a checked disparity that would have won (ties go
//   to the smaller d) or failed the winner's uniqueness test over the full
//   range. Unlike the full range's test, a checked disparity next to the
//   winner (g_1 = minDisparity - 1 with step 1, b = minDisparity) counts as
//   well. The sub-pixel step does not change.
//
//   Texture, uniqueness and the guard are checked in that order; the result
//   is the same whichever fails first.
//
//   Right winner (for the left-right check, from the same costs): for the
//   right pixel (xr, y), the d of least C(xr + d, y, d) over the d whose left
//   pixel xr + d lies in the region's (or the band's) columns, with
//   d <= top(xr + d); ties go to the smallest d;
//   minDisparity - 1 where no d qualifies. Texture and uniqueness play no part.
//   With the guard, a right pixel that has a winner in the range also weighs
//   the checked g_k whose left pixel xr + g_k lies in the region's columns
//   (it counts there: xr + r <= W - 1 holds for these right pixels): if the
//   least of their C(xr + g_k, y, g_k) is <= the range's least, the winner
//   is the smallest g_k holding it (a smaller d wins ties), written as
//   min(g_k, minDisparity - 2) so that g_1 = minDisparity - 1 (step 1) does
//   not read as "no winner". The left-right check then rejects a left pixel
//   whose right partner matches better below the range, as the full range's
//   would (for disp12MaxDiff <= 1 exactly, except at the range's bottom).
//
//   Only the output rows in `rows` are written (both maps); every row's result
//   depends on the input rows of its window alone, so stripes of a frame give
//   the whole frame's result.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <vector>

#include "sad/sad.hpp"

namespace horopter {

MatchRegion matchRegion(int width, int height, const StereoParams& params) {
  const int r = params.blockSize / 2;
  const int maxD = params.minDisparity + params.numDisparities - 1;
  MatchRegion region;
  region.x0 = std::max(r, r + maxD);
  region.x1 = std::min(width - r, width - r + params.minDisparity);
  region.y0 = r;
  region.y1 = height - r;
  region.bandX0 = region.x0;
  if (params.leftBand > 0)
    region.bandX0 = std::clamp(r + params.minDisparity + params.leftBand - 1, r, region.x0);
  return region;
}

namespace scalar {

namespace {

// Decides one left pixel from its costs over its range (costs[k] is the cost
// of disparity minDisparity + k, k < count: numDisparities in the region,
// top(x) - minDisparity + 1 in the band). Returns the disparity in 1/16 px
// or invalid. guardLeast: the least cost of the checked disparities below
// the range that count for this pixel (INT32_MAX: none).
std::int16_t decidePixel(const std::int32_t* costs, int count, int textureSum,
                         std::int32_t guardLeast, const StereoParams& params) {
  const std::int16_t invalid = invalidDisparity(params);

  int best = 0;
  for (int k = 1; k < count; ++k) {
    if (costs[k] < costs[best]) best = k;  // strict: the smallest d wins ties
  }

  if (params.textureThreshold > 0 && textureSum < params.textureThreshold) return invalid;

  if (params.uniquenessRatio > 0) {
    const std::int64_t c0 = costs[best];
    const std::int64_t limit = c0 + c0 * params.uniquenessRatio / 100;
    for (int k = 0; k < count; ++k) {
      if (std::abs(k - best) > 1 && costs[k] <= limit) return invalid;
    }
  }

  if (guardLeast != std::numeric_limits<std::int32_t>::max()) {
    const std::int64_t c0 = costs[best];
    const std::int64_t limit = c0 + c0 * params.uniquenessRatio / 100;  // c0 when the ratio is 0
    if (guardLeast <= limit) return invalid;
  }

  // A range of one disparity has no neighbour to fit: offset 0.
  const std::int64_t c0 = costs[best];
  std::int64_t cm = best > 0 ? costs[best - 1] : costs[std::min(best + 1, count - 1)];
  std::int64_t cp = best < count - 1 ? costs[best + 1] : costs[std::max(best - 1, 0)];
  const std::int64_t den = cm + cp - 2 * c0 + std::abs(cm - cp);
  const std::int64_t off = den > 0 ? (cm - cp) * 256 / den : 0;
  const std::int64_t d = params.minDisparity + best;
  return static_cast<std::int16_t>((d * 256 + off + 8) >> 4);
}

}  // namespace

void matchColumns(const ConstImageView& left, const ConstImageView& right,
                  const ConstImageView& texture, const StereoParams& params,
                  const BelowRangeGuard& guard, const ImageView& disparity,
                  const ImageView& winnerRight, RowRange rows, const ColumnWindow& window) {
  const int width = left.width;
  const int height = left.height;
  const int r = params.blockSize / 2;
  const int count = params.numDisparities;
  const int minD = params.minDisparity;
  const auto noWinner = static_cast<std::int16_t>(minD - 1);

  MatchRegion region = matchRegion(width, height, params);
  region.y0 = std::max(region.y0, rows.begin);
  region.y1 = std::min(region.y1, rows.end);
  if (region.empty()) return;
  // The left pixels costed: [cx0, cx1), band and region.
  const int cx0 = region.bandX0;
  const int cx1 = std::min(region.x1, window.costedEnd);
  const int leftEnd = std::min(cx1, window.leftEnd);
  const int rightEnd = std::clamp(window.rightEnd, 0, width);
  // How many disparities pixel x searches (its top is x - r in the band).
  const auto countAt = [&](int x) { return std::min(count, x - r - minD + 1); };

  // Column sums over the window's height, for the columns the windows of the
  // costed pixels touch: columnCost[k * width + x] = sum over |j| <= r of
  // |L(x, y+j) - R(x - d, y+j)| where x - d >= 0, and columnTexture[x] =
  // sum of T(x, y+j). They slide down one row at a time: add the row
  // entering the window, subtract the row leaving it.
  const int xa = cx0 - r;
  const int xb = cx1 + r;  // columns [xa, xb)
  std::vector<std::int32_t> columnCost(static_cast<std::size_t>(count) * width, 0);
  std::vector<std::int32_t> columnTexture(width, 0);
  const bool useTexture = params.textureThreshold > 0;

  // The guard's checked disparities, with their column sums over the columns
  // whose right pixel lies inside the image (x - g < W), and the pixels
  // where they count (x < W - r + g).
  const int guards = guardCount(params, guard);
  std::vector<std::int32_t> guardColumn(static_cast<std::size_t>(guards) * width, 0);
  const auto guardDisparity = [&](int n) { return minD - (n + 1) * guard.step; };
  const auto guardColumnEnd = [&](int n) { return std::min(xb, width + guardDisparity(n)); };
  const auto guardPixelEnd = [&](int n) { return std::min(cx1, width - r + guardDisparity(n)); };

  auto addRow = [&](int row, int sign) {
    const auto* l = left.row<std::uint8_t>(row);
    const auto* rr = right.row<std::uint8_t>(row);
    for (int k = 0; k < count; ++k) {
      const int d = minD + k;
      std::int32_t* col = &columnCost[static_cast<std::size_t>(k) * width];
      for (int x = std::max(xa, d); x < xb; ++x)
        col[x] += sign * std::abs(l[x] - rr[x - d]);
    }
    for (int n = 0; n < guards; ++n) {
      const int g = guardDisparity(n);
      std::int32_t* col = &guardColumn[static_cast<std::size_t>(n) * width];
      for (int x = std::max(xa, g); x < guardColumnEnd(n); ++x)
        col[x] += sign * std::abs(l[x] - rr[x - g]);
    }
    if (useTexture) {
      const auto* t = texture.row<std::uint8_t>(row);
      for (int x = xa; x < xb; ++x)
        columnTexture[x] += sign * t[x];
    }
  };
  for (int j = region.y0 - r; j <= region.y0 + r; ++j)
    addRow(j, +1);

  std::vector<std::int32_t> costs(static_cast<std::size_t>(count) * width);  // [x][k]
  std::vector<std::int32_t> rightBestCost(width);
  std::vector<std::int16_t> rightWinner(width);
  std::vector<std::int32_t> guardLeast(width);
  std::vector<std::int32_t> guardCost(static_cast<std::size_t>(guards) * width);  // [n][x]
  for (int y = region.y0; y < region.y1; ++y) {
    if (y > region.y0) {
      addRow(y + r, +1);
      addRow(y - r - 1, -1);
    }

    // Window sums along the row, for every costed column whose window fits
    // the right image at d: a running sum that takes in the column entering
    // the window and drops the one leaving it.
    for (int k = 0; k < count; ++k) {
      const std::int32_t* col = &columnCost[static_cast<std::size_t>(k) * width];
      const int xs = std::max(cx0, r + minD + k);
      if (xs >= cx1) continue;
      std::int32_t sum = 0;
      for (int i = -r; i <= r; ++i)
        sum += col[xs + i];
      for (int x = xs; x < cx1; ++x) {
        if (x > xs) sum += col[x + r] - col[x - r - 1];
        costs[static_cast<std::size_t>(x) * count + k] = sum;
      }
    }

    // The guard's least cost per pixel, from running sums as above.
    std::fill(guardLeast.begin(), guardLeast.end(), std::numeric_limits<std::int32_t>::max());
    for (int n = 0; n < guards; ++n) {
      const std::int32_t* col = &guardColumn[static_cast<std::size_t>(n) * width];
      std::int32_t sum = 0;
      for (int x = cx0; x < guardPixelEnd(n); ++x) {
        if (x == cx0) {
          for (int i = -r; i <= r; ++i)
            sum += col[x + i];
        } else {
          sum += col[x + r] - col[x - r - 1];
        }
        guardLeast[x] = std::min(guardLeast[x], sum);
        guardCost[static_cast<std::size_t>(n) * width + x] = sum;
      }
    }

    auto* outDisparity = disparity.row<std::int16_t>(y);
    for (int x = cx0; x < leftEnd; ++x) {
      int textureSum = 0;
      if (useTexture) {
        for (int i = -r; i <= r; ++i)
          textureSum += columnTexture[x + i];
      }
      outDisparity[x] = decidePixel(&costs[static_cast<std::size_t>(x) * count], countAt(x),
                                    textureSum, guardLeast[x], params);
    }

    // The right view's winner: left pixels in increasing x reach each right
    // pixel in increasing d, so a strict < keeps the smallest d on ties.
    std::fill(rightBestCost.begin(), rightBestCost.end(), std::numeric_limits<std::int32_t>::max());
    std::fill(rightWinner.begin(), rightWinner.end(), noWinner);
    for (int x = cx0; x < cx1; ++x) {
      for (int k = 0; k < countAt(x); ++k) {
        const int xr = x - (minD + k);
        const std::int32_t c = costs[static_cast<std::size_t>(x) * count + k];
        if (c < rightBestCost[xr]) {
          rightBestCost[xr] = c;
          rightWinner[xr] = static_cast<std::int16_t>(minD + k);
        }
      }
    }

    // The guard's candidates for the right pixels that have a winner: the
    // checked disparities in increasing g (n decreasing), a strict < keeping
    // the smallest g, then <= against the range's least (g is smaller).
    for (int xr = 0; xr < width && guards > 0; ++xr) {
      if (rightBestCost[xr] == std::numeric_limits<std::int32_t>::max()) continue;
      std::int32_t least = std::numeric_limits<std::int32_t>::max();
      int leastD = 0;
      for (int n = guards - 1; n >= 0; --n) {
        const int x = xr + guardDisparity(n);
        if (x < cx0 || x >= guardPixelEnd(n)) continue;
        const std::int32_t c = guardCost[static_cast<std::size_t>(n) * width + x];
        if (c < least) {
          least = c;
          leastD = guardDisparity(n);
        }
      }
      if (least <= rightBestCost[xr])
        rightWinner[xr] = static_cast<std::int16_t>(std::min(leastD, minD - 2));
    }
    std::copy_n(rightWinner.begin(), rightEnd, winnerRight.row<std::int16_t>(y));
  }
}

void matchBlocks(const ConstImageView& left, const ConstImageView& right,
                 const ConstImageView& texture, const StereoParams& params,
                 const BelowRangeGuard& guard, const ImageView& disparity,
                 const ImageView& winnerRight, RowRange rows) {
  const std::int16_t invalid = invalidDisparity(params);
  const auto noWinner = static_cast<std::int16_t>(params.minDisparity - 1);
  for (int y = rows.begin; y < rows.end; ++y) {
    std::fill_n(disparity.row<std::int16_t>(y), left.width, invalid);
    std::fill_n(winnerRight.row<std::int16_t>(y), left.width, noWinner);
  }
  matchColumns(left, right, texture, params, guard, disparity, winnerRight, rows, ColumnWindow{});
}

void matchLeftBand(const ConstImageView& left, const ConstImageView& right,
                   const ConstImageView& texture, const StereoParams& params,
                   const BelowRangeGuard& guard, const ImageView& disparity,
                   const ImageView& winnerRight, RowRange rows) {
  const MatchRegion region = matchRegion(left.width, left.height, params);
  if (region.empty() || region.bandX0 == region.x0) return;
  matchColumns(left, right, texture, params, guard, disparity, winnerRight, rows,
               leftBandWindow(region, params, guard));
}

ColumnWindow leftBandWindow(const MatchRegion& region, const StereoParams& params,
                            const BelowRangeGuard& guard) {
  // A band pixel x < x0 is a candidate of the right pixels x - d, d down to
  // the lowest disparity checked (minDisparity, or the guard's lowest g);
  // their other candidates lie left of that right end + maxD.
  const int lowest = params.minDisparity - guardCount(params, guard) * guard.step;
  ColumnWindow window;
  window.rightEnd = region.x0 - lowest;
  window.costedEnd = window.rightEnd + params.minDisparity + params.numDisparities - 1;
  window.leftEnd = region.x0;
  return window;
}

}  // namespace scalar
}  // namespace horopter
