// AVX2 speckle filter: run-based union-find labelling over per-row bitmasks.
//
// Strategy
//   Rows: each row is copied into a padded scratch row (one invalid pixel on
//   the left, invalid pixels up to a multiple of 64 on the right), so every
//   load is in bounds and the padding joins nothing. The previous row's copy
//   is kept for the vertical test.
//   Masks: 32 pixels per step (two 16-lane vectors) give three bitmasks per
//   row, one bit per pixel: valid (d != invalid), joinLeft (valid, left
//   neighbour valid, |d - left| <= speckleRange) and joinUp (the same with the
//   pixel above). |a - b| is max - min taken as unsigned 16 bits, exact for
//   any int16 pair, and compared unsigned against min(speckleRange, 65535).
//   The compare masks are packed to bytes and read with movemask.
//   Runs: a run is a maximal stretch of pixels joined left to right. Run
//   starts are valid & ~joinLeft, run ends are valid & ~(joinLeft >> 1); both
//   come in the same order, so tzcnt / blsr over the two masks lists the
//   row's runs. Every run gets a label: its index in the frame's run table.
//   Vertical joins: walking the joinUp bits, each set bit unites the two runs
//   it lies in (found by popcount of the run starts up to it, this row's and
//   the previous row's), then the walk skips to the end of the shorter of
//   the two runs, so every overlapping pair of runs is united at most once.
//   Union-find: path halving, and union by smaller index, so a parent is
//   never larger than its child and the root of a set is its first run.
//   Counting: one pass in index order flattens every parent to its root
//   (parents come first, so are already flat) and adds the run lengths to
//   the roots; runs whose root counted at most speckleWindowSize are filled
//   with the invalid marker.
//   Scratch (padded rows, masks, run tables) is thread-local and only grows.
//   The blobs are the connected components of the same joins as the scalar
//   flood fill, so the result is bit-exact with the scalar reference.
#include <immintrin.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "common/cpu_features.hpp"
#include "occlusion/occlusion.hpp"

namespace horopter::avx2 {

namespace {

constexpr int kWordBits = 64;

struct Scratch {
  std::vector<std::int16_t> rows;      // two padded rows
  std::vector<std::uint64_t> masks;    // valid, joinLeft, joinUp words of one row
  std::vector<std::uint64_t> starts;   // run-start words of this row and the previous one
  std::vector<std::int32_t> before;    // per start word, runs of its row in earlier words
  std::vector<std::int32_t> runStart;  // per run, first x
  std::vector<std::int32_t> runEnd;    // per run, last x
  std::vector<std::int32_t> parent;    // per run, union-find parent (then root)
  std::vector<std::int64_t> count;     // per root run, pixels of its blob (past 2^31 in huge maps)
  std::vector<std::int32_t> rowBegin;  // first run of each row, plus the total
};

template <typename T>
HOROPTER_AVX2_TARGET void growTo(std::vector<T>& v, std::size_t n) {
  if (v.size() < n) v.resize(n);
}

// All lanes where |a - b| <= range (range as unsigned 16 bits).
HOROPTER_AVX2_TARGET inline __m256i closeEnough(__m256i a, __m256i b, __m256i range) {
  const __m256i diff = _mm256_sub_epi16(_mm256_max_epi16(a, b), _mm256_min_epi16(a, b));
  return _mm256_cmpeq_epi16(_mm256_min_epu16(diff, range), diff);
}

// One bit per 16-bit lane of two all-or-nothing masks, pixel order.
HOROPTER_AVX2_TARGET inline std::uint32_t laneBits(__m256i lo, __m256i hi) {
  const __m256i packed = _mm256_permute4x64_epi64(_mm256_packs_epi16(lo, hi), 0xD8);
  return static_cast<std::uint32_t>(_mm256_movemask_epi8(packed));
}

// Bits of 32 pixels starting at x of padded rows (x - 1 is readable).
HOROPTER_AVX2_TARGET inline void rowBits(const std::int16_t* cur, const std::int16_t* up, int x,
                                         __m256i invalid, __m256i range, std::uint32_t& valid,
                                         std::uint32_t& joinLeft, std::uint32_t& joinUp) {
  __m256i bad[2], left[2], above[2];
  for (int h = 0; h < 2; ++h) {
    const int at = x + 16 * h;
    const __m256i c = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(cur + at));
    const __m256i l = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(cur + at - 1));
    const __m256i u = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(up + at));
    const __m256i badC = _mm256_cmpeq_epi16(c, invalid);
    const __m256i badL = _mm256_cmpeq_epi16(l, invalid);
    const __m256i badU = _mm256_cmpeq_epi16(u, invalid);
    bad[h] = badC;
    left[h] = _mm256_andnot_si256(_mm256_or_si256(badC, badL), closeEnough(c, l, range));
    above[h] = _mm256_andnot_si256(_mm256_or_si256(badC, badU), closeEnough(c, u, range));
  }
  valid = ~laneBits(bad[0], bad[1]);
  joinLeft = laneBits(left[0], left[1]);
  joinUp = laneBits(above[0], above[1]);
}

// First set bit at or after x in the words, or words * 64 when none.
HOROPTER_AVX2_TARGET inline int nextSetBit(const std::uint64_t* bits, int words, int x) {
  int w = x / kWordBits;
  if (w >= words) return words * kWordBits;
  std::uint64_t m = bits[w] & (~std::uint64_t{0} << (x % kWordBits));
  while (m == 0) {
    if (++w >= words) return words * kWordBits;
    m = bits[w];
  }
  return w * kWordBits + static_cast<int>(_tzcnt_u64(m));
}

// The run holding pixel x of a row: its row's runs that start at or before x, less one.
HOROPTER_AVX2_TARGET inline std::int32_t runAt(const std::uint64_t* starts,
                                               const std::int32_t* before, std::int32_t rowFirst,
                                               int x) {
  const int w = x / kWordBits;
  const auto upToX = _bzhi_u64(starts[w], static_cast<unsigned>(x % kWordBits) + 1);
  return rowFirst + before[w] + static_cast<std::int32_t>(_mm_popcnt_u64(upToX)) - 1;
}

HOROPTER_AVX2_TARGET inline std::int32_t findRoot(std::int32_t* parent, std::int32_t a) {
  while (parent[a] != a) {
    parent[a] = parent[parent[a]];  // path halving
    a = parent[a];
  }
  return a;
}

HOROPTER_AVX2_TARGET inline void unite(std::int32_t* parent, std::int32_t a, std::int32_t b) {
  a = findRoot(parent, a);
  b = findRoot(parent, b);
  if (a < b) {
    parent[b] = a;
  } else if (b < a) {
    parent[a] = b;
  }
}

}  // namespace

HOROPTER_AVX2_TARGET void filterSpeckles(const ImageView& disparity, const StereoParams& params) {
  if (params.speckleWindowSize == 0) return;
  const int width = disparity.width;
  const int height = disparity.height;
  if (width <= 0 || height <= 0) return;
  const std::int16_t invalid = invalidDisparity(params);
  const int words = (width + kWordBits - 1) / kWordBits;
  const int paddedWidth = words * kWordBits;
  const int rowStride = paddedWidth + 32;  // left pad, pixels, right pad
  const std::size_t maxRuns = static_cast<std::size_t>(width) * height;  // range 0: 1 px runs

  thread_local Scratch s;
  growTo(s.rows, 2 * static_cast<std::size_t>(rowStride));
  growTo(s.masks, 3 * static_cast<std::size_t>(words));
  growTo(s.starts, 2 * static_cast<std::size_t>(words));
  growTo(s.before, 2 * static_cast<std::size_t>(words));
  growTo(s.runStart, maxRuns);
  growTo(s.runEnd, maxRuns);
  growTo(s.parent, maxRuns);
  growTo(s.count, maxRuns);
  growTo(s.rowBegin, static_cast<std::size_t>(height) + 1);
  std::fill(s.rows.begin(), s.rows.begin() + 2 * rowStride, invalid);

  std::int16_t* cur = s.rows.data();
  std::int16_t* up = cur + rowStride;
  std::uint64_t* validBits = s.masks.data();
  std::uint64_t* leftBits = validBits + words;
  std::uint64_t* upBits = leftBits + words;
  std::uint64_t* startBits = s.starts.data();
  std::uint64_t* startBitsUp = startBits + words;
  std::int32_t* before = s.before.data();
  std::int32_t* beforeUp = before + words;
  std::int32_t* runStart = s.runStart.data();
  std::int32_t* runEnd = s.runEnd.data();
  std::int32_t* parent = s.parent.data();
  std::int64_t* count = s.count.data();
  const __m256i invalidV = _mm256_set1_epi16(invalid);
  const __m256i rangeV =
      _mm256_set1_epi16(static_cast<std::int16_t>(std::min(params.speckleRange, 0xFFFF)));

  std::int32_t runs = 0;
  for (int y = 0; y < height; ++y) {
    std::swap(cur, up);
    std::swap(startBits, startBitsUp);
    std::swap(before, beforeUp);
    std::memcpy(cur + 1, disparity.row<std::int16_t>(y), sizeof(std::int16_t) * width);

    // Masks of this row: pixel x sits at cur[1 + x].
    for (int w = 0; w < words; ++w) {
      std::uint32_t v[2], l[2], u[2];
      for (int h = 0; h < 2; ++h) {
        const int x = w * kWordBits + 32 * h;
        rowBits(cur, up, 1 + x, invalidV, rangeV, v[h], l[h], u[h]);
      }
      validBits[w] = v[0] | std::uint64_t{v[1]} << 32;
      leftBits[w] = l[0] | std::uint64_t{l[1]} << 32;
      upBits[w] = u[0] | std::uint64_t{u[1]} << 32;
    }

    // Runs of this row: starts and ends in the same order.
    const std::int32_t first = runs;
    s.rowBegin[y] = first;
    std::int32_t ends = runs;
    for (int w = 0; w < words; ++w) {
      const std::uint64_t nextLeft = w + 1 < words ? leftBits[w + 1] : 0;
      std::uint64_t starts = validBits[w] & ~leftBits[w];
      startBits[w] = starts;
      before[w] = runs - first;
      std::uint64_t stops = validBits[w] & ~((leftBits[w] >> 1) | (nextLeft << 63));
      const int base = w * kWordBits;
      while (starts != 0) {
        runStart[runs++] = base + static_cast<int>(_tzcnt_u64(starts));
        starts = _blsr_u64(starts);
      }
      while (stops != 0) {
        runEnd[ends++] = base + static_cast<int>(_tzcnt_u64(stops));
        stops = _blsr_u64(stops);
      }
    }
    for (std::int32_t r = first; r < runs; ++r)
      parent[r] = r;
    if (y == 0) continue;

    // Vertical joins: one union per overlapping pair of runs with a joinUp bit.
    const std::int32_t firstUp = s.rowBegin[y - 1];
    const int limit = words * kWordBits;
    for (int x = nextSetBit(upBits, words, 0); x < limit;) {
      const std::int32_t c = runAt(startBits, before, first, x);
      const std::int32_t a = runAt(startBitsUp, beforeUp, firstUp, x);
      unite(parent, c, a);
      x = nextSetBit(upBits, words, std::min(runEnd[c], runEnd[a]) + 1);
    }
  }
  s.rowBegin[height] = runs;

  // Roots come first in index order, so one pass flattens and counts.
  for (std::int32_t r = 0; r < runs; ++r) {
    const std::int32_t root = parent[parent[r]];
    parent[r] = root;
    count[r] = 0;
    count[root] += runEnd[r] - runStart[r] + 1;
  }

  for (int y = 0; y < height; ++y) {
    std::int16_t* d = disparity.row<std::int16_t>(y);
    for (std::int32_t r = s.rowBegin[y]; r < s.rowBegin[y + 1]; ++r) {
      if (count[parent[r]] <= params.speckleWindowSize)
        std::fill(d + runStart[r], d + runEnd[r] + 1, invalid);
    }
  }
}

}  // namespace horopter::avx2
