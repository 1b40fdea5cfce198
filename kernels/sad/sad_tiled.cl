// OpenCL C 1.2 SAD block matching shaped for GPUs: the same outputs as
// sad_match (sad.cl), bit for bit (sad_scalar.cpp states the semantics).
//
// Strategy
//   sad_match gives one work-item a strip of rows, which suits a CPU and
//   starves a GPU. Here two kernels share a cost volume in global memory:
//   - sad_costs: a 2-D NDRange over the region's pixels in fixed
//     work-groups (launch.cpp: 64 x 4 by default; the tuning variants below change the
//     shape and the passes, not the costs). For each pass of perPass planes,
//     the group sums the window's height for its columns plus the window's
//     margins into local memory (one value per plane, column and row of the
//     tile; a left pixel read once for the pass's planes), then each
//     work-item sums the window's width from there and writes its pixel's
//     costs. Planes: the range's disparities (minD + k, k < numD), the
//     guard's checked ones (minD - (n + 1) * guardStep, n < guardCount) and,
//     when the texture test is on, the texture's window sum. A guard plane
//     holds INT_MAX where the disparity does not count (x - g + radius >=
//     width: the window would leave the right image); no real cost reaches
//     it (at most 255 * 255^2).
//   - sad_decide: one work-item per position (x, y) of the rows asked for,
//     for both views, so that the two read a row of the volume while it is
//     in the cache (one pass over the volume from memory, not two):
//     - sad_tiled_left: the left pixel x reads its planes once (adjacent
//       work-items read adjacent words of a plane): winner (strict <: the
//       smallest d wins ties), texture, uniqueness, guard and the integer
//       equiangular fit, as decidePixel in the reference.
//     - sad_tiled_right: the right pixel x replays the reference's choice:
//       the least C(x + d, d) over the d whose left pixel lies in the
//       region's columns (strict <, d increasing), then the guard's
//       candidates in increasing g (strict <), which win when <= the
//       range's least, written as min(g, minD - 2).
//   Volume layout: costs[((y - yA) * planes + p) * width + x] (uint16 for
//   blocks up to 15, whose costs fit, halving the volume's traffic; int32
//   past them: sad_tiled_cost, sad_tiled_store), yA the first
//   region row of the call's rows: plane-major within a row, so every
//   kernel reads and writes consecutive x in consecutive work-items.
//   Rows of [rowBegin, rowEnd) outside the region and columns outside
//   [x0, x1) get the invalid markers from sad_decide.

// A cost of the volume: int32, or uint16 when `narrow` (blocks up to 15,
// where every cost is at most 255 * 15^2 < 0xFFFF), 0xFFFF standing for
// INT_MAX (a guard plane's "does not count").
int sad_tiled_cost(__global const int* restrict costs, size_t i, int narrow) {
  if (narrow) {
    const int v = ((__global const ushort*)costs)[i];
    return v == 0xFFFF ? INT_MAX : v;
  }
  return costs[i];
}

void sad_tiled_store(__global int* restrict costs, size_t i, int narrow, int c) {
  if (narrow)
    ((__global ushort*)costs)[i] = (ushort)min(c, 0xFFFF);
  else
    costs[i] = c;
}

// Tuning variants (kernels/opencl/tiled_variant.hpp; HOROPTER_OPENCL_TILED)
// set these as build options; the defaults are the default variant's
// (tiled_variant.hpp; its block, 9, is a build option of its own program).
// The most planes one pass of sad_costs handles (perPass <= this): each left
// pixel is read once for all of them.
#ifndef SAD_TILED_PASS_PLANES
#define SAD_TILED_PASS_PLANES 4
#endif
// 1: the column sums spread linearly over the whole group; 0: row by row,
// work-item (lx, ly) takes the row ly's columns lx, lx + tileW, ...
#ifndef SAD_TILED_SPREAD
#define SAD_TILED_SPREAD 1
#endif
// 0: a group takes all the planes; n > 0: a group takes n passes, the
// NDRange's third dimension (get_group_id(2)) runs over the planes.
#ifndef SAD_TILED_SPLIT
#define SAD_TILED_SPLIT 1
#endif
// Rows per work-item: a work-item's column sums slide down this many rows
// (two rows' terms a step, not the window's height), the tile is tileH *
// SAD_TILED_ROWS rows tall.
#ifndef SAD_TILED_ROWS
#define SAD_TILED_ROWS 4
#endif
// Defined: the program serves this window radius only (launch.cpp uses it
// for that block size alone), so the compiler sees fixed loop counts.
// #define SAD_TILED_RADIUS 4

__kernel void sad_costs(__global const uchar* restrict left, __global const uchar* restrict right,
                        __global const uchar* restrict texture, int inStride, int width, int minD,
                        int numD, int radius, int x0, int x1, int yA, int yB, int guardStep,
                        int guardCount, int useTexture, int perPass, int narrow,
                        __global int* restrict costs, __local int* restrict vsum) {
#ifdef SAD_TILED_RADIUS
  radius = SAD_TILED_RADIUS;  // equal to the argument (launch.cpp)
#endif
  const int lx = get_local_id(0), ly = get_local_id(1);
  const int tileW = get_local_size(0);
  const int bx = x0 + get_group_id(0) * tileW;
  const int x = bx + lx;
  const int tileH = get_local_size(1);
  const int by = yA + get_group_id(1) * tileH * SAD_TILED_ROWS;
  const int tw = tileW + 2 * radius;  // the tile's columns [bx - radius, bx + tileW + radius)
  const int slab = tileH * SAD_TILED_ROWS * tw;  // one plane's column sums, [row][column]
  const int planes = numD + guardCount + useTexture;
#if SAD_TILED_SPLIT > 0
  const int pBegin = get_group_id(2) * SAD_TILED_SPLIT * perPass;
  const int pEnd = min(planes, pBegin + SAD_TILED_SPLIT * perPass);
#else
  const int pBegin = 0, pEnd = planes;
#endif
  for (int p0 = pBegin; p0 < pEnd; p0 += perPass) {
    // Per plane of the pass: kind 0 range, 1 guard, 2 texture, 3 none.
    int kind[SAD_TILED_PASS_PLANES], d[SAD_TILED_PASS_PLANES];
#pragma unroll
    for (int q = 0; q < SAD_TILED_PASS_PLANES; ++q) {
      const int p = p0 + q;
      kind[q] = (q >= perPass || p >= planes) ? 3 : (p < numD ? 0 : (p < numD + guardCount ? 1 : 2));
      d[q] = kind[q] == 0 ? minD + p : (kind[q] == 1 ? minD - (p - numD + 1) * guardStep : 0);
    }
    // The column sums of the tile's rows by + ty * SAD_TILED_ROWS (ty <
    // tileH) and, sliding down, of the SAD_TILED_ROWS - 1 rows below each.
#if SAD_TILED_SPREAD
    // Spread over the whole group (consecutive work-items take consecutive
    // columns, whole warps go idle at the end).
    for (int e = ly * tileW + lx; e < tileH * tw; e += tileW * tileH) {
      const int ty = e / tw, tx = e - ty * tw;
#else
    for (int e = ly * tw + lx; e < (ly + 1) * tw; e += tileW) {
      const int ty = ly, tx = e - ly * tw;
#endif
      const int gx = bx - radius + tx;
      const int gy = by + ty * SAD_TILED_ROWS;
      int s[SAD_TILED_PASS_PLANES];
      int use[SAD_TILED_PASS_PLANES];
#pragma unroll
      for (int q = 0; q < SAD_TILED_PASS_PLANES; ++q) {
        s[q] = 0;
        // Columns past the region's windows, or whose right pixel lies past
        // the image (guard planes only), are never summed into a cost kept.
        use[q] = kind[q] != 3 && gx < x1 + radius && gx - d[q] < width;
      }
      int top = (gy - radius) * inStride + gx;  // the window's first row
      int at = top;
      // None past the image's columns, or below the rows asked for.
      const int rowsIn = gx < x1 + radius && gy < yB ? 2 * radius + 1 : 0;
      for (int j = 0; j < rowsIn; ++j, at += inStride) {
        const int lv = left[at];
#pragma unroll
        for (int q = 0; q < SAD_TILED_PASS_PLANES; ++q) {
          if (use[q]) s[q] += kind[q] == 2 ? (int)texture[at] : abs(lv - (int)right[at - d[q]]);
        }
      }
      __local int* out = vsum + ty * SAD_TILED_ROWS * tw + tx;
#pragma unroll
      for (int q = 0; q < SAD_TILED_PASS_PLANES; ++q) {
        if (q < perPass) out[q * slab] = s[q];
      }
#if SAD_TILED_ROWS > 1
      // Row gy + r from row gy + r - 1: the row entering the window (at,
      // one past its last) in, the one leaving it (top) out.
      const int rowsDown = rowsIn > 0 ? min(SAD_TILED_ROWS, yB - gy) : 0;
      for (int r = 1; r < rowsDown; ++r, at += inStride, top += inStride) {
        const int lin = left[at], lout = left[top];
#pragma unroll
        for (int q = 0; q < SAD_TILED_PASS_PLANES; ++q) {
          if (use[q])
            s[q] += kind[q] == 2 ? (int)texture[at] - (int)texture[top]
                                 : abs(lin - (int)right[at - d[q]]) - abs(lout - (int)right[top - d[q]]);
        }
        out += tw;
#pragma unroll
        for (int q = 0; q < SAD_TILED_PASS_PLANES; ++q) {
          if (q < perPass) out[q * slab] = s[q];
        }
      }
#endif
    }
    barrier(CLK_LOCAL_MEM_FENCE);
#pragma unroll
    for (int r = 0; r < SAD_TILED_ROWS; ++r) {
      const int y = by + ly * SAD_TILED_ROWS + r;
      if (y < yB && x < x1) {
#pragma unroll
        for (int q = 0; q < SAD_TILED_PASS_PLANES; ++q) {
          if (kind[q] == 3) continue;
          __local const int* mine = vsum + q * slab + (ly * SAD_TILED_ROWS + r) * tw + lx;
          int c = 0;
          for (int i = 0; i <= 2 * radius; ++i)
            c += mine[i];
          if (kind[q] == 1 && x - d[q] + radius >= width) c = INT_MAX;
          sad_tiled_store(costs, ((size_t)(y - yA) * planes + p0 + q) * width + x, narrow, c);
        }
      }
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
}

long sad_tiled_floor_div16(long v) {
  long q = v / 16;
  if (v % 16 < 0) q -= 1;
  return q;
}

// The left pixel (x, y)'s disparity in 1/16 px, or the invalid marker.
short sad_tiled_left(__global const int* restrict costs, int narrow, int width, int minD,
                     int numD, int textureThreshold, int uniquenessRatio, int x0, int x1, int yA,
                     int yB, int guardCount, int x, int y) {
  short result = (short)((minD - 1) * 16);
  if (y >= yA && y < yB && x >= x0 && x < x1) {
    const int useTexture = textureThreshold > 0;
    const int planes = numD + guardCount + useTexture;
    const size_t c = (size_t)(y - yA) * planes * width + x;  // plane p at c + p * width
    // One pass over the range: the winner (strict <: the smallest d on
    // ties), its neighbours' costs, and the least cost of the d with
    // |d - best| > 1 (uniqueness). A new winner at k has every j <= k - 2
    // outside its neighbourhood: their least is the prefix minimum to k - 2.
    int best = 0;
    int bestCost = sad_tiled_cost(costs, c, narrow);
    int cmCost = 0, cpCost = 0;  // C(best - 1), C(best + 1) where they exist
    int outside = INT_MAX;       // least C(j), |j - best| > 1, j < k
    int prefix1 = bestCost;      // least C(0 .. k - 1)
    int prefix2 = INT_MAX;       // least C(0 .. k - 2)
    int previous = bestCost;     // C(k - 1)
    for (int k = 1; k < numD; ++k) {
      const int v = sad_tiled_cost(costs, c + (size_t)k * width, narrow);
      if (v < bestCost) {
        bestCost = v;
        best = k;
        cmCost = previous;
        outside = prefix2;
      } else if (k == best + 1) {
        cpCost = v;
      } else {
        outside = min(outside, v);
      }
      prefix2 = prefix1;
      prefix1 = min(prefix1, v);
      previous = v;
    }
    int ok = !(useTexture &&
               sad_tiled_cost(costs, c + (size_t)(numD + guardCount) * width, narrow) <
                   textureThreshold);
    const long c0 = bestCost;
    const long limit = c0 + c0 * uniquenessRatio / 100;
    if (ok && uniquenessRatio > 0) ok = !(outside != INT_MAX && (long)outside <= limit);
    if (ok && guardCount > 0) {
      int guardLeast = INT_MAX;  // INT_MAX: the plane does not count here
      for (int n = 0; n < guardCount; ++n)
        guardLeast = min(guardLeast, sad_tiled_cost(costs, c + (size_t)(numD + n) * width, narrow));
      ok = !(guardLeast != INT_MAX && (long)guardLeast <= limit);
    }
    if (ok) {
      // At the ends of the range the missing side mirrors the other one.
      const long cm = best > 0 ? cmCost : cpCost;
      const long cp = best < numD - 1 ? cpCost : cmCost;
      const long den = cm + cp - 2 * c0 + (cm > cp ? cm - cp : cp - cm);
      const long off = den > 0 ? (cm - cp) * 256 / den : 0;
      const long d = (long)(minD + best);
      result = (short)sad_tiled_floor_div16(d * 256 + off + 8);
    }
  }
  return result;
}

// The right pixel (xr, y)'s winner, or minD - 1 where no d qualifies.
short sad_tiled_right(__global const int* restrict costs, int narrow, int width, int minD,
                      int numD, int useTexture, int x0, int x1, int yA, int yB, int guardStep,
                      int guardCount, int xr, int y) {
  const int maxD = minD + numD - 1;
  short result = (short)(minD - 1);
  if (y >= yA && y < yB && xr >= x0 - maxD && xr < x1 - minD) {
    const int planes = numD + guardCount + useTexture;
    const size_t c = (size_t)(y - yA) * planes * width;  // plane p at c + p * width
    // The d whose left pixel xr + d lies in [x0, x1): never empty here.
    const int kLo = max(0, x0 - xr - minD);
    const int kHi = min(numD - 1, x1 - 1 - xr - minD);
    int best = INT_MAX;
    int bestK = kLo;
    for (int k = kLo; k <= kHi; ++k) {
      const int v = sad_tiled_cost(costs, c + (size_t)k * width + xr + minD + k, narrow);
      if (v < best) {
        best = v;
        bestK = k;
      }
    }
    result = (short)(minD + bestK);
    int least = INT_MAX;
    int leastD = 0;
    for (int n = guardCount - 1; n >= 0; --n) {
      const int g = minD - (n + 1) * guardStep;
      const int x = xr + g;
      if (x < x0 || x >= x1) continue;
      const int v = sad_tiled_cost(costs, c + (size_t)(numD + n) * width + x, narrow);
      if (v < least) {
        least = v;
        leastD = g;
      }
    }
    if (least <= best) result = (short)min(leastD, minD - 2);
  }
  return result;
}

// Both views' results of one row position: the left pixel x and the right
// pixel x read the same row of the volume while it is in the cache.
__kernel void sad_decide(__global const int* restrict costs, int narrow, int width, int minD,
                         int numD,
                         int textureThreshold, int uniquenessRatio, int x0, int x1, int yA, int yB,
                         int rowBegin, int rowEnd, int guardStep, int guardCount,
                         __global short* restrict disparity, __global short* restrict winnerRight,
                         int outStride) {
  const int x = get_global_id(0);
  const int y = rowBegin + get_global_id(1);
  if (x >= width || y >= rowEnd) return;
  disparity[y * outStride + x] =
      sad_tiled_left(costs, narrow, width, minD, numD, textureThreshold, uniquenessRatio, x0, x1,
                     yA, yB, guardCount, x, y);
  winnerRight[y * outStride + x] =
      sad_tiled_right(costs, narrow, width, minD, numD, textureThreshold > 0, x0, x1, yA, yB,
                      guardStep, guardCount, x, y);
}
