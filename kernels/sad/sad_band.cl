// OpenCL C 1.2: the left band of SAD block matching (StereoParams::leftBand),
// after sad_match or sad_costs/sad_decide have done the region: bit-exact
// with scalar::matchLeftBand (sad_scalar.cpp states the semantics).
//
// Strategy
//   The band is a small triangle beside the region (its columns [bandX0, x0),
//   pixel x searching d in [minD, x - radius]), so this kernel is the
//   reference's matchColumns over the columns [bandX0, costedEnd) written as
//   plain loops, for either shape of the region's matcher: one work-item per
//   strip of rows (work-groups of one), sliding the column sums down the
//   strip as sad_match does. Per strip, in global scratch:
//   - colsum ([column][k]): window-height sums of |L(x) - R(x - d)|, d =
//     minD + k, 0 where x - d < 0 (no pixel whose window fits reads those);
//     colTex ([column]) the texture's, gcol ([column][n]) the guard's, for
//     g = minD - (n + 1) * guardStep where the right pixel x - g lies in
//     the image;
//   - costs ([pixel][k]) and gcost ([pixel][n]): the current row's window
//     sums, from running sums along the row;
//   - rbestCost, rbestD ([right pixel]): the right view's winners.
//   It writes the band's left pixels and the right winners xr in [0,
//   rightEnd), those with a candidate in the band (a guard's included:
//   rightEnd = x0 - the least disparity costed; every candidate of those
//   lies left of costedEnd; scalar::leftBandWindow), only in the rows
//   [rowBegin, rowEnd) the host passes (the requested rows within the
//   region's), over what the region's kernels wrote. Costs are exact int32 sums; the uniqueness
//   limit and the sub-pixel fit use 64-bit longs, as the reference.

// floor(v / 16): the reference's arithmetic shift, spelled out.
long sad_band_floor_div16(long v) {
  long q = v / 16;
  if (v % 16 < 0) q -= 1;
  return q;
}

// Column sums of the columns [xa, xa + wc): input row `rowIn`'s terms added
// and, when rowOut >= 0, row rowOut's taken away (the window sliding down).
void sad_band_columns(__global const uchar* restrict left, __global const uchar* restrict right,
                      __global const uchar* restrict texture, int inStride, int width, int minD,
                      int numD, int useTexture, int guardStep, int guardCount, int xa, int wc,
                      int rowIn, int rowOut, __global int* restrict colsum,
                      __global int* restrict colTex, __global int* restrict gcol) {
  __global const uchar* lIn = left + rowIn * inStride;
  __global const uchar* rIn = right + rowIn * inStride;
  const int out = rowOut >= 0;
  __global const uchar* lOut = left + (out ? rowOut : rowIn) * inStride;
  __global const uchar* rOut = right + (out ? rowOut : rowIn) * inStride;
  for (int c = 0; c < wc; ++c) {
    const int x = xa + c;
    const int li = lIn[x], lo = lOut[x];
    __global int* col = colsum + c * numD;
    // d = minD + k <= x: the right pixel x - d lies in the image.
    const int ks = min(numD, x - minD + 1);
    __global const uchar* ri = rIn + x - minD;
    __global const uchar* ro = rOut + x - minD;
    if (out) {
      for (int k = 0; k < ks; ++k)
        col[k] += abs(li - (int)ri[-k]) - abs(lo - (int)ro[-k]);
    } else {
      for (int k = 0; k < ks; ++k)
        col[k] += abs(li - (int)ri[-k]);
    }
    for (int n = 0; n < guardCount; ++n) {
      const int g = minD - (n + 1) * guardStep;
      if (x < g || x - g >= width) continue;
      gcol[c * guardCount + n] +=
          abs(li - (int)rIn[x - g]) - (out ? abs(lo - (int)rOut[x - g]) : 0);
    }
    if (useTexture)
      colTex[c] += (int)texture[rowIn * inStride + x] -
                   (out ? (int)texture[rowOut * inStride + x] : 0);
  }
}

// The reference's decidePixel: the disparity of a left pixel from its
// `count` costs (minD + k, k < count), 1/16 px, or the invalid marker.
short sad_band_decide(__global const int* restrict costs, int count, int textureSum,
                      int guardLeast, int minD, int textureThreshold, int uniquenessRatio) {
  const short invalid = (short)((minD - 1) * 16);
  int least = INT_MAX;
  for (int k = 0; k < count; ++k)
    least = min(least, costs[k]);
  int best = count;  // the smallest d holding the least wins ties
  for (int k = 0; k < count; ++k)
    best = min(best, costs[k] == least ? k : count);
  if (textureThreshold > 0 && textureSum < textureThreshold) return invalid;
  const long c0 = costs[best];
  const long limit = c0 + c0 * uniquenessRatio / 100;  // c0 when the ratio is 0
  if (uniquenessRatio > 0) {
    for (int k = 0; k < count; ++k)
      if (abs(k - best) > 1 && (long)costs[k] <= limit) return invalid;
  }
  if (guardLeast != INT_MAX && (long)guardLeast <= limit) return invalid;
  // The ends of the pixel's own range mirror the other side; a range of one
  // disparity has no neighbour to fit: offset 0.
  const long cm = best > 0 ? costs[best - 1] : costs[min(best + 1, count - 1)];
  const long cp = best < count - 1 ? costs[best + 1] : costs[max(best - 1, 0)];
  const long den = cm + cp - 2 * c0 + (cm > cp ? cm - cp : cp - cm);
  const long off = den > 0 ? (cm - cp) * 256 / den : 0;
  const long d = (long)(minD + best);
  return (short)sad_band_floor_div16(d * 256 + off + 8);
}

__kernel void sad_band(__global const uchar* restrict left, __global const uchar* restrict right,
                       __global const uchar* restrict texture, int inStride, int width, int minD,
                       int numD, int radius, int textureThreshold, int uniquenessRatio,
                       int bandX0, int x0, int costedEnd, int rightEnd, int rowBegin, int rowEnd,
                       int stripRows, __global short* restrict disparity,
                       __global short* restrict winnerRight, int outStride,
                       __global int* restrict colsumAll, __global int* restrict colTexAll,
                       __global int* restrict costsAll, __global int* restrict rbestCostAll,
                       __global int* restrict rbestDAll, int guardStep, int guardCount,
                       __global int* restrict gcolAll, __global int* restrict gcostAll) {
  const int strip = get_global_id(0);
  const int ys = rowBegin + strip * stripRows;
  const int ye = min(rowEnd, ys + stripRows);
  if (ys >= ye) return;

  const int cx0 = bandX0, cx1 = costedEnd;  // the left pixels costed
  const int pixels = cx1 - cx0;
  const int xa = cx0 - radius;
  const int wc = pixels + 2 * radius;  // columns [xa, xa + wc)
  const int useTexture = textureThreshold > 0;
  const short noWinner = (short)(minD - 1);
  __global int* restrict colsum = colsumAll + (size_t)strip * wc * numD;
  __global int* restrict colTex = colTexAll + (size_t)strip * wc;
  __global int* restrict gcol = gcolAll + (size_t)strip * wc * guardCount;
  __global int* restrict costs = costsAll + (size_t)strip * pixels * numD;
  __global int* restrict gcost = gcostAll + (size_t)strip * pixels * guardCount;
  __global int* restrict rbestCost = rbestCostAll + (size_t)strip * width;
  __global int* restrict rbestD = rbestDAll + (size_t)strip * width;

  for (int c = 0; c < wc; ++c) {
    for (int k = 0; k < numD; ++k)
      colsum[c * numD + k] = 0;
    for (int n = 0; n < guardCount; ++n)
      gcol[c * guardCount + n] = 0;
    colTex[c] = 0;
  }
  for (int j = ys - radius; j <= ys + radius; ++j)
    sad_band_columns(left, right, texture, inStride, width, minD, numD, useTexture, guardStep,
                     guardCount, xa, wc, j, -1, colsum, colTex, gcol);

  for (int y = ys; y < ye; ++y) {
    if (y > ys)
      sad_band_columns(left, right, texture, inStride, width, minD, numD, useTexture, guardStep,
                       guardCount, xa, wc, y + radius, y - radius - 1, colsum, colTex, gcol);

    // Window sums along the row: pixel x's from x - 1's, + the column
    // entering, - the one leaving (consecutive k: vector code). Exact for
    // the disparities whose window fits the right image (k < count(x): the
    // window's columns are all >= d); the others are never read.
    for (int k = 0; k < numD; ++k) {
      int sum = 0;
      for (int c = 0; c <= 2 * radius; ++c)
        sum += colsum[c * numD + k];
      costs[k] = sum;
    }
    for (int x = cx0 + 1; x < cx1; ++x) {
      __global const int* enter = colsum + (x + radius - xa) * numD;
      __global const int* leave = colsum + (x - radius - 1 - xa) * numD;
      __global const int* prev = costs + (x - 1 - cx0) * numD;
      __global int* cur = costs + (x - cx0) * numD;
      for (int k = 0; k < numD; ++k)
        cur[k] = prev[k] + enter[k] - leave[k];
    }
    // The guard's, for the pixels where g counts (x - g + radius < width).
    for (int n = 0; n < guardCount; ++n) {
      const int g = minD - (n + 1) * guardStep;
      const int xe = min(cx1, width - radius + g);
      int sum = 0;
      for (int x = cx0; x < xe; ++x) {
        if (x == cx0) {
          for (int i = -radius; i <= radius; ++i)
            sum += gcol[(x + i - xa) * guardCount + n];
        } else {
          sum += gcol[(x + radius - xa) * guardCount + n] -
                 gcol[(x - radius - 1 - xa) * guardCount + n];
        }
        gcost[(x - cx0) * guardCount + n] = sum;
      }
    }

    // The band's left pixels, each over its own range.
    __global short* outRow = disparity + y * outStride;
    for (int x = cx0; x < x0; ++x) {
      int textureSum = 0;
      if (useTexture) {
        for (int i = -radius; i <= radius; ++i)
          textureSum += colTex[x + i - xa];
      }
      int guardLeast = INT_MAX;
      for (int n = 0; n < guardCount; ++n) {
        const int g = minD - (n + 1) * guardStep;
        if (x < width - radius + g) guardLeast = min(guardLeast, gcost[(x - cx0) * guardCount + n]);
      }
      const int count = min(numD, x - radius - minD + 1);
      outRow[x] = sad_band_decide(costs + (x - cx0) * numD, count, textureSum, guardLeast, minD,
                                  textureThreshold, uniquenessRatio);
    }

    // The right view's winners: left pixels in increasing x reach each right
    // pixel in increasing d, so a strict < keeps the smallest d on ties.
    // Every right pixel a candidate reaches (x - d < cx1 - minD) or written.
    for (int xr = 0; xr < max(cx1 - minD, rightEnd); ++xr) {
      rbestCost[xr] = INT_MAX;
      rbestD[xr] = noWinner;
    }
    for (int x = cx0; x < cx1; ++x) {
      const int count = min(numD, x - radius - minD + 1);
      __global const int* cost = costs + (x - cx0) * numD;
      __global int* rc = rbestCost + x - minD;  // right pixel x - d at rc[-k]
      __global int* rd = rbestD + x - minD;
      for (int k = 0; k < count; ++k) {
        const int c = cost[k];
        const int old = rc[-k];
        const int better = c < old;
        rc[-k] = better ? c : old;
        rd[-k] = better ? minD + k : rd[-k];
      }
    }
    // The guard's candidates for the right pixels that have a winner, in
    // increasing g (n decreasing) with a strict <, winning when <= the
    // range's least; written as min(g, minD - 2), never "no winner".
    __global short* winRow = winnerRight + y * outStride;
    for (int xr = 0; xr < rightEnd; ++xr) {
      int winner = rbestD[xr];
      if (guardCount > 0 && rbestCost[xr] != INT_MAX) {
        int least = INT_MAX;
        int leastD = 0;
        for (int n = guardCount - 1; n >= 0; --n) {
          const int g = minD - (n + 1) * guardStep;
          const int x = xr + g;
          if (x < cx0 || x >= min(cx1, width - radius + g)) continue;
          const int c = gcost[(x - cx0) * guardCount + n];
          if (c < least) {
            least = c;
            leastD = g;
          }
        }
        if (least <= rbestCost[xr]) winner = min(leastD, minD - 2);
      }
      winRow[xr] = (short)winner;
    }
  }
}
