// OpenCL C 1.2 invalid-aware median that fills holes: bit-exact with the
// scalar reference (median_scalar.cpp states the semantics).
//
// Strategy
//   One work-item per 8 consecutive output pixels of a row, in explicit
//   short8 vectors (lane i = pixel x0 + i), so that a CPU device (PoCL)
//   runs the sort in SIMD registers and a GPU runs it in registers too.
//   The k x k window becomes k*k vectors; pixels outside the image and
//   invalid pixels become INT16_MAX, so they sort to the end and the n valid
//   values occupy ranks 0..n-1 (a valid INT16_MAX ties with them and is the
//   same value). The lower median is rank (n - 1) / 2, an element of the
//   window, as the reference.
//   The window is sorted by a fixed network with constant indices, so the
//   compiler keeps it in registers and drops every comparator whose result
//   only feeds ranks above the highest one ever selected ((k*k - 1) / 2).
//   The networks are Batcher's odd-even merge sort for 32 (5x5) and 16 (3x3)
//   inputs with the comparators that touch positions >= k*k removed: those
//   positions would hold the sentinel, which never moves, so the removed
//   comparators could only ever have been no-ops.
//   (The first version, one pixel per work-item with k*k rounds of odd-even
//   transposition over a loop-indexed array, took 35 ms per 640x480 frame
//   on PoCL; PoCL did not vectorise it across work-items.)

#define MEDIAN_SENTINEL 32767
#define MEDIAN_INLINE static inline __attribute__((always_inline))

// Compare-exchange of two window entries, lane by lane: the smaller first.
#define CE(a, b)                       \
  {                                    \
    const short8 lo = min(v[a], v[b]); \
    v[b] = max(v[a], v[b]);            \
    v[a] = lo;                         \
  }

// Lane-wise rank r (0..last) of the sorted window, with constant indices
// only (a variable index would push the window out of registers).
MEDIAN_INLINE short8 select_rank(const short8* v, short8 r, int last) {
  short8 out = v[0];
  for (int i = 1; i <= last; ++i)
    out = select(out, v[i], r == (short8)(i));
  return out;
}

MEDIAN_INLINE short8 median5x5(short8* v, short8 n) {
  // 140 comparators.
  CE(0, 1)
  CE(2, 3) CE(4, 5) CE(6, 7) CE(8, 9) CE(10, 11) CE(12, 13) CE(14, 15) CE(16, 17) CE(18, 19)
      CE(20, 21) CE(22, 23) CE(0, 2) CE(1, 3) CE(4, 6) CE(5, 7) CE(8, 10) CE(9, 11) CE(12, 14) CE(
          13, 15) CE(16, 18) CE(17, 19) CE(20, 22) CE(21, 23) CE(1, 2) CE(5, 6) CE(9, 10) CE(13, 14)
          CE(17, 18) CE(21, 22) CE(0, 4) CE(1, 5) CE(2, 6) CE(3, 7) CE(8, 12) CE(9, 13) CE(10, 14)
              CE(11, 15) CE(16, 20) CE(17, 21) CE(18, 22) CE(19, 23) CE(2, 4) CE(3, 5) CE(
                  10, 12) CE(11, 13) CE(18, 20) CE(19, 21) CE(1, 2) CE(3, 4) CE(5, 6) CE(9, 10)
                  CE(11, 12) CE(13, 14) CE(17, 18) CE(19, 20) CE(21, 22) CE(0, 8) CE(1, 9) CE(2, 10)
                      CE(3, 11) CE(4, 12) CE(5, 13) CE(6, 14) CE(7, 15) CE(16, 24) CE(4, 8) CE(5, 9)
                          CE(6, 10) CE(7, 11) CE(20, 24) CE(2, 4) CE(3, 5) CE(6, 8) CE(7, 9)
                              CE(10, 12) CE(11, 13) CE(18, 20) CE(19, 21) CE(22, 24) CE(1, 2) CE(
                                  3, 4) CE(5, 6) CE(7, 8) CE(9, 10) CE(11, 12) CE(13, 14) CE(17, 18)
                                  CE(19, 20) CE(21, 22) CE(23, 24) CE(0, 16) CE(1, 17) CE(2, 18)
                                      CE(3, 19) CE(4, 20) CE(5, 21) CE(6, 22) CE(7, 23) CE(
                                          8, 24) CE(8, 16) CE(9, 17) CE(10, 18) CE(11, 19)
                                          CE(12, 20) CE(13, 21) CE(14, 22) CE(15, 23) CE(4, 8) CE(
                                              5, 9) CE(6, 10) CE(7, 11) CE(12, 16)
                                              CE(13, 17) CE(14, 18) CE(15, 19) CE(20, 24) CE(
                                                  2, 4) CE(3, 5) CE(6, 8) CE(7, 9) CE(10, 12)
                                                  CE(11, 13) CE(14, 16) CE(15, 17) CE(18, 20)
                                                      CE(19, 21) CE(22, 24) CE(1, 2) CE(3, 4) CE(
                                                          5, 6) CE(7, 8) CE(9, 10) CE(11, 12)
                                                          CE(13, 14) CE(15, 16) CE(17, 18) CE(
                                                              19, 20) CE(21, 22)
                                                              CE(23, 24) return select_rank(
                                                                  v,
                                                                  (n - (short8)(1)) / (short8)(2),
                                                                  12);
}

MEDIAN_INLINE short8 median3x3(short8* v, short8 n) {
  // 28 comparators.
  CE(0, 1)
  CE(2, 3) CE(4, 5) CE(6, 7) CE(0, 2) CE(1, 3) CE(4, 6) CE(5, 7) CE(1, 2) CE(5, 6) CE(0, 4) CE(1, 5)
      CE(2, 6) CE(3, 7) CE(2, 4) CE(3, 5) CE(1, 2) CE(3, 4) CE(5, 6) CE(0, 8) CE(4, 8) CE(2, 4)
          CE(3, 5) CE(6, 8) CE(1, 2) CE(3, 4) CE(5, 6)
              CE(7, 8) return select_rank(v, (n - (short8)(1)) / (short8)(2), 4);
}

// Row yy, columns x .. x+7; lanes outside the image read as `invalid`.
MEDIAN_INLINE short8 load8(__global const short* src, int stride, int width, int height,
                           short invalid, int x, int yy) {
  if (yy < 0 || yy >= height) return (short8)(invalid);
  __global const short* row = src + yy * stride;
  short8 s;
  if (x >= 0 && x + 7 < width) {
    s = vload8(0, row + x);
  } else {  // a border: lane by lane, clamped reads, outside lanes discarded
    short e[8];
    for (int i = 0; i < 8; ++i) {
      const int xx = x + i;
      e[i] = xx >= 0 && xx < width ? row[xx] : invalid;
    }
    s = vload8(0, e);
  }
  return s;
}

// Loads the k x k windows of the 8 pixels (k = 2h + 1, h a constant at each
// call site so the loops unroll and the indices are constants); returns how
// many values of each lane's window are valid.
MEDIAN_INLINE short8 load_windows(__global const short* src, int stride, int width, int height,
                                  short invalid, int x0, int y, int h, short8* v) {
  short8 n = (short8)(0);
#pragma unroll
  for (int j = -h; j <= h; ++j) {
#pragma unroll
    for (int i = -h; i <= h; ++i) {
      const short8 raw = load8(src, stride, width, height, invalid, x0 + i, y + j);
      const short8 valid = raw != (short8)(invalid);  // a true lane is -1
      n -= valid;
      v[(j + h) * (2 * h + 1) + (i + h)] = select((short8)(MEDIAN_SENTINEL), raw, valid);
    }
  }
  return n;
}

// Global size: (ceil(width / 8), rows). Lanes past the right edge are
// computed on discarded values and not stored.
__kernel void median_filter(__global const short* src, __global short* dst, int stride, int width,
                            int height, int kernelSize, int minValid, short invalid, int rowBegin,
                            int rowEnd) {
  const int x0 = 8 * (int)get_global_id(0);
  const int y = rowBegin + (int)get_global_id(1);
  if (x0 >= width || y >= rowEnd) return;
  const short8 centreValid = load8(src, stride, width, height, invalid, x0, y) != (short8)(invalid);
  short8 n, m;
  if (kernelSize == 5) {
    short8 v[25];
    n = load_windows(src, stride, width, height, invalid, x0, y, 2, v);
    m = median5x5(v, n);
  } else {
    short8 v[9];
    n = load_windows(src, stride, width, height, invalid, x0, y, 1, v);
    m = median3x3(v, n);
  }
  // With a valid centre n >= 1, so rank (n - 1) / 2 is a valid value (or a
  // sentinel tied with a real INT16_MAX disparity: the same value).
  const short8 fill = centreValid | (n >= (short8)(minValid));
  const short8 out = select((short8)(invalid), m, fill);
  __global short* row = dst + y * stride;
  if (x0 + 7 < width) {
    vstore8(out, 0, row + x0);
  } else {
    short e[8];
    vstore8(out, 0, e);
    for (int i = 0; x0 + i < width; ++i)
      row[x0 + i] = e[i];
  }
}
