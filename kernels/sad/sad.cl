// OpenCL C 1.2 SAD block matching with winner-take-all, texture and
// uniqueness checks, sub-pixel refinement and the right view's winners:
// bit-exact with the scalar reference (sad_scalar.cpp states the semantics).
//
// Strategy
//   One work-item per horizontal strip of output rows (work-groups of one
//   work-item): the strip is swept top to bottom with running sums, as a CPU
//   would, because the target here is PoCL on the CPU, whose compiler turns
//   the inner loops over disparities into vector code. A GPU runs it too,
//   correctly but without the parallelism a GPU-shaped kernel would have.
//   - colsum (global scratch, per work-item, [column][disparity]): the
//     window-height column sums |L - R| of every disparity; one row step adds
//     the entering row and subtracts the leaving one. colTex: the same for
//     the texture image.
//   - hsum (private, [disparity]): the window sums of the current pixel,
//     sliding along the row: + the entering column, - the leaving one.
//   - The decision per pixel is a min over the disparities, then the first
//     disparity holding it (the smallest d wins ties), an or-reduction for
//     the uniqueness test, and the integer equiangular fit.
//   - The right view's winner: the left pixels of a row in increasing x reach
//     each right pixel in increasing d, so a strict < keeps the smallest d,
//     as the reference's loop.
//   - The guard below the range (guardCount > 0, zone-limited matching):
//     gcol (global scratch, [column][checked disparity]) and ghsum (private)
//     slide as colsum and hsum do, for the disparities minD - (n + 1) *
//     guardStep; columns whose right pixel lies past the image stay 0 and
//     the pixels whose window would reach them skip that disparity. Their
//     costs join the right view's candidates before the range's (a left
//     pixel x reaches right pixel x - g before x - d for every d in the
//     range), stored as index min(g - minD, -2) (-2: g = minD - 1, written
//     as minD - 2, as the reference); INT_MIN marks "none".
//   Costs are exact int32 sums (at most 255 * 255^2 < 2^31); the uniqueness
//   limit and the sub-pixel fit use 64-bit longs as the reference. Rows of
//   the range outside the matching region are filled with the invalid
//   marker (and minDisparity - 1 for the right winner) by the same strip.

#define SAD_MAX_DISPARITIES 1024

long sad_floor_div16(long v) {
  long q = v / 16;
  if (v % 16 < 0) q -= 1;
  return q;
}

__kernel void sad_match(__global const uchar* restrict left, __global const uchar* restrict right,
                        __global const uchar* restrict texture, int inStride, int width,
                        int minD, int numD, int radius, int textureThreshold, int uniquenessRatio,
                        int x0, int x1, int y0, int y1, int rowBegin, int rowEnd, int stripRows,
                        __global short* restrict disparity, __global short* restrict winnerRight,
                        int outStride, __global int* restrict colsumAll,
                        __global int* restrict colTexAll, __global int* restrict rbestCostAll,
                        __global int* restrict rbestDAll, int guardStep, int guardCount,
                        __global int* restrict gcolAll) {
  const int strip = get_global_id(0);
  const int ys = rowBegin + strip * stripRows;
  const int ye = min(rowEnd, ys + stripRows);
  if (ys >= ye) return;
  const short invalid = (short)((minD - 1) * 16);
  const short noWinner = (short)(minD - 1);
  for (int y = ys; y < ye; ++y) {
    for (int x = 0; x < width; ++x) {
      disparity[y * outStride + x] = invalid;
      winnerRight[y * outStride + x] = noWinner;
    }
  }
  const int yA = max(ys, y0);
  const int yB = min(ye, y1);
  if (yA >= yB || x0 >= x1) return;

  const int xa = x0 - radius;
  const int wc = x1 + radius - xa;  // columns [xa, xa + wc)
  const int maxD = minD + numD - 1;
  const int useTexture = textureThreshold > 0;
  __global int* restrict colsum = colsumAll + (size_t)strip * wc * numD;
  __global int* restrict colTex = colTexAll + (size_t)strip * wc;
  __global int* restrict rbestCost = rbestCostAll + (size_t)strip * width;
  __global int* restrict rbestD = rbestDAll + (size_t)strip * width;
  __global int* restrict gcol = gcolAll + (size_t)strip * wc * guardCount;

  // Column sums of the first row's window.
  for (int c = 0; c < wc; ++c) {
    for (int k = 0; k < numD; ++k)
      colsum[c * numD + k] = 0;
    colTex[c] = 0;
    for (int n = 0; n < guardCount; ++n)
      gcol[c * guardCount + n] = 0;
  }
  for (int j = yA - radius; j <= yA + radius; ++j) {
    __global const uchar* l = left + j * inStride + xa;
    __global const uchar* r = right + j * inStride + xa - minD;
    for (int c = 0; c < wc; ++c) {
      const int lv = l[c];
      __global int* col = colsum + c * numD;
      for (int k = 0; k < numD; ++k)
        col[k] += abs(lv - (int)r[c - k]);
    }
    if (useTexture) {
      __global const uchar* t = texture + j * inStride + xa;
      for (int c = 0; c < wc; ++c)
        colTex[c] += t[c];
    }
    for (int n = 0; n < guardCount; ++n) {
      const int g = minD - (n + 1) * guardStep;
      __global const uchar* rg = right + j * inStride;
      for (int c = 0; c < wc && xa + c - g < width; ++c)
        gcol[c * guardCount + n] += abs((int)l[c] - (int)rg[xa + c - g]);
    }
  }

  int hsum[SAD_MAX_DISPARITIES];
  int ghsum[SAD_MAX_DISPARITIES];
  for (int y = yA; y < yB; ++y) {
    if (y > yA) {
      __global const uchar* lIn = left + (y + radius) * inStride + xa;
      __global const uchar* rIn = right + (y + radius) * inStride + xa - minD;
      __global const uchar* lOut = left + (y - radius - 1) * inStride + xa;
      __global const uchar* rOut = right + (y - radius - 1) * inStride + xa - minD;
      for (int c = 0; c < wc; ++c) {
        const int li = lIn[c];
        const int lo = lOut[c];
        __global int* col = colsum + c * numD;
        for (int k = 0; k < numD; ++k)
          col[k] += abs(li - (int)rIn[c - k]) - abs(lo - (int)rOut[c - k]);
      }
      if (useTexture) {
        __global const uchar* tIn = texture + (y + radius) * inStride + xa;
        __global const uchar* tOut = texture + (y - radius - 1) * inStride + xa;
        for (int c = 0; c < wc; ++c)
          colTex[c] += (int)tIn[c] - (int)tOut[c];
      }
      for (int n = 0; n < guardCount; ++n) {
        const int g = minD - (n + 1) * guardStep;
        __global const uchar* gIn = right + (y + radius) * inStride;
        __global const uchar* gOut = right + (y - radius - 1) * inStride;
        for (int c = 0; c < wc && xa + c - g < width; ++c)
          gcol[c * guardCount + n] += abs((int)lIn[c] - (int)gIn[xa + c - g]) -
                                      abs((int)lOut[c] - (int)gOut[xa + c - g]);
      }
    }

    for (int k = 0; k < numD; ++k)
      hsum[k] = 0;
    int texSum = 0;
    for (int c = 0; c <= 2 * radius; ++c) {
      for (int k = 0; k < numD; ++k)
        hsum[k] += colsum[c * numD + k];
      texSum += colTex[c];
      for (int n = 0; n < guardCount; ++n)
        ghsum[n] = (c == 0 ? 0 : ghsum[n]) + gcol[c * guardCount + n];
    }
    for (int xr = x0 - maxD; xr < x1 - minD; ++xr) {
      rbestCost[xr] = INT_MAX;
      rbestD[xr] = INT_MIN;
    }

    __global short* outRow = disparity + y * outStride;
    for (int x = x0; x < x1; ++x) {
      if (x > x0) {
        __global const int* enter = colsum + (x + radius - xa) * numD;
        __global const int* leave = colsum + (x - radius - 1 - xa) * numD;
        for (int k = 0; k < numD; ++k)
          hsum[k] += enter[k] - leave[k];
        texSum += colTex[x + radius - xa] - colTex[x - radius - 1 - xa];
        __global const int* gEnter = gcol + (x + radius - xa) * guardCount;
        __global const int* gLeave = gcol + (x - radius - 1 - xa) * guardCount;
        for (int n = 0; n < guardCount; ++n)
          ghsum[n] += gEnter[n] - gLeave[n];
      }

      int bestCost = INT_MAX;
      for (int k = 0; k < numD; ++k)
        bestCost = min(bestCost, hsum[k]);
      int best = numD;
      for (int k = 0; k < numD; ++k)
        best = min(best, hsum[k] == bestCost ? k : numD);

      // The guard's right candidates first (smaller d), for the right pixels
      // that have a winner (x - g < x1 - minD) and where g counts.
      for (int n = guardCount - 1; n >= 0; --n) {
        const int g = minD - (n + 1) * guardStep;
        const int xr = x - g;
        if (xr >= x1 - minD || x - g + radius >= width) continue;
        const int c = ghsum[n];
        if (c < rbestCost[xr]) {
          rbestCost[xr] = c;
          rbestD[xr] = min(g - minD, -2);
        }
      }
      // The right view's candidates: right pixel x - d gets C(x, d).
      __global int* rc = rbestCost + x - minD;
      __global int* rd = rbestD + x - minD;
      for (int k = 0; k < numD; ++k) {
        const int c = hsum[k];
        const int old = rc[-k];
        const int better = c < old;
        rc[-k] = better ? c : old;
        rd[-k] = better ? k : rd[-k];
      }

      short result = invalid;
      int ok = !(useTexture && texSum < textureThreshold);
      if (ok && uniquenessRatio > 0) {
        const long c0 = bestCost;
        const long limit = c0 + c0 * uniquenessRatio / 100;
        const int limit32 = (int)min(limit, (long)INT_MAX);
        int clash = 0;
        for (int k = 0; k < numD; ++k)
          clash |= (hsum[k] <= limit32) & (abs(k - best) > 1);
        ok = !clash;
      }
      if (ok && guardCount > 0) {
        // The least checked cost below the range, over the disparities whose
        // window lies inside the right image (x - g + radius < width).
        int guardLeast = INT_MAX;
        for (int n = 0; n < guardCount; ++n) {
          const int g = minD - (n + 1) * guardStep;
          if (x - g + radius < width) guardLeast = min(guardLeast, ghsum[n]);
        }
        const long c0 = bestCost;
        const long limit = c0 + c0 * uniquenessRatio / 100;
        ok = !(guardCount > 0 && guardLeast != INT_MAX && (long)guardLeast <= limit);
      }
      if (ok) {
        const long c0 = bestCost;
        const long cm = best > 0 ? hsum[best - 1] : hsum[best + 1];
        const long cp = best < numD - 1 ? hsum[best + 1] : hsum[best - 1];
        const long den = cm + cp - 2 * c0 + (cm > cp ? cm - cp : cp - cm);
        const long off = den > 0 ? (cm - cp) * 256 / den : 0;
        const long d = (long)(minD + best);
        result = (short)sad_floor_div16(d * 256 + off + 8);
      }
      outRow[x] = result;
    }

    __global short* winRow = winnerRight + y * outStride;
    for (int xr = x0 - maxD; xr < x1 - minD; ++xr) {
      if (rbestD[xr] != INT_MIN) winRow[xr] = (short)(minD + rbestD[xr]);
    }
  }
}
