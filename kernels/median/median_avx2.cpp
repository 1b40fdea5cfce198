// AVX2 median: bit-exact with the scalar reference.
//
// Strategy
//   Lanes: 16 int16 output pixels per vector, x .. x+15 of one row.
//   Invalid values and positions outside the image become INT16_MAX, so they
//   sort after every valid value (a valid INT16_MAX ties with them and is
//   still the same value). With n valid values in the window, the lower
//   median is then rank (n - 1) / 2 of the sorted window, n <= k*k, so only
//   the lowest (k*k + 1) / 2 ranks are ever needed.
//   Per output row, in scratch rows padded by h columns of INT16_MAX on each
//   side (so borders need no special case and vector loads never leave the
//   scratch):
//     1. the k input rows, converted (cached across output rows);
//     2. each column of k values sorted by a network, and its valid count;
//     3. (k = 5) each pair of adjacent sorted columns merged to 10, shared
//        by the two output pixels whose window holds that pair;
//     4. per output vector, Batcher odd-even merges of the sorted pieces;
//        merge outputs above the highest rank needed are never used and the
//        compiler drops their comparators. n is the sum of k column counts;
//        rank (n - 1) / 2 is selected by a blend tree over its bits, and the
//        fill rule (centre valid, or n >= minValid) picks median or v.
//        Fast paths: a vector whose 16 windows are all fully valid needs the
//        middle rank only (fewer comparators survive), one whose windows
//        are all empty is v.
//   The scratch is 64-byte aligned with whole-line rows: split stores cost.
//   Tails: the scratch rows are padded to whole vectors; the last, partial
//   output vector of a row goes through a small buffer, so only the row's
//   own pixels are written.
//   bit-exact with the scalar reference.
#include <immintrin.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "common/cpu_features.hpp"
#include "median/median.hpp"

namespace horopter::avx2 {

namespace {

constexpr int kLanes = 16;
constexpr std::int16_t kMax = INT16_MAX;

// GCC 12 with AddressSanitizer, or at -O2 (RelWithDebInfo), reports false
// -Warray-bounds hits inside the fully inlined networks (it confuses the small
// arrays of different merge levels); the indices are compile-time and in range.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Warray-bounds"
#endif

// N vectors by value (std::array<__m256i, N> would drop __m256i's alignment attribute).
template <int N>
struct Vecs {
  static constexpr int kSize = N;
  __m256i v[N > 0 ? N : 1];
  HOROPTER_AVX2_TARGET __m256i& operator[](int i) { return v[i]; }
  HOROPTER_AVX2_TARGET const __m256i& operator[](int i) const { return v[i]; }
};

HOROPTER_AVX2_TARGET inline __m256i load(const std::int16_t* p) {
  return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
}
HOROPTER_AVX2_TARGET inline void store(std::int16_t* p, __m256i v) {
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), v);
}

// Batcher's odd-even merge of sorted a and b, any sizes (Knuth 5.3.4): merge
// the even-indexed and the odd-indexed elements separately, then one row of
// comparators between the two results.
// Everything below is forced inline: the networks must become straight-line
// code on registers, and merge outputs nobody reads must be visible as dead.
#define HOROPTER_INLINE HOROPTER_AVX2_TARGET inline __attribute__((always_inline))

template <int A, int B>
HOROPTER_INLINE Vecs<A + B> merge(const Vecs<A>& a, const Vecs<B>& b) {
  Vecs<A + B> z;
  if constexpr (A == 0 || B == 0) {
    for (int i = 0; i < A; ++i)
      z[i] = a[i];
    for (int i = 0; i < B; ++i)
      z[A + i] = b[i];
  } else if constexpr (A == 1 && B == 1) {
    z[0] = _mm256_min_epi16(a[0], b[0]);
    z[1] = _mm256_max_epi16(a[0], b[0]);
  } else {
    Vecs<(A + 1) / 2> aEven;
    Vecs<A / 2> aOdd;
    Vecs<(B + 1) / 2> bEven;
    Vecs<B / 2> bOdd;
    for (int i = 0; i < (A + 1) / 2; ++i)
      aEven[i] = a[2 * i];
    for (int i = 0; i < A / 2; ++i)
      aOdd[i] = a[2 * i + 1];
    for (int i = 0; i < (B + 1) / 2; ++i)
      bEven[i] = b[2 * i];
    for (int i = 0; i < B / 2; ++i)
      bOdd[i] = b[2 * i + 1];
    const auto v = merge<(A + 1) / 2, (B + 1) / 2>(aEven, bEven);
    const auto w = merge<A / 2, B / 2>(aOdd, bOdd);
    constexpr int nv = decltype(v)::kSize;
    constexpr int nw = decltype(w)::kSize;
    z[0] = v[0];
    for (int i = 0; i < nw; ++i) {
      if (i + 1 < nv) {
        z[2 * i + 1] = _mm256_min_epi16(w[i], v[i + 1]);
        z[2 * i + 2] = _mm256_max_epi16(w[i], v[i + 1]);
      } else {
        z[2 * i + 1] = w[i];
      }
    }
    if (nv == nw + 2) z[A + B - 1] = v[nv - 1];
  }
  return z;
}

template <int N>
HOROPTER_INLINE Vecs<N> sortNetwork(const Vecs<N>& a) {
  if constexpr (N <= 1) {
    return a;
  } else {
    Vecs<N / 2> lo;
    Vecs<N - N / 2> hi;
    for (int i = 0; i < N / 2; ++i)
      lo[i] = a[i];
    for (int i = N / 2; i < N; ++i)
      hi[i - N / 2] = a[i];
    return merge<N / 2, N - N / 2>(sortNetwork<N / 2>(lo), sortNetwork<N - N / 2>(hi));
  }
}

// s[r] per lane, r in [0, N) (other r give some element of s).
template <int N>
HOROPTER_INLINE __m256i selectRank(const Vecs<N>& s, __m256i r) {
  if constexpr (N == 1) {
    return s[0];
  } else {
    // The lowest bit of r picks within pairs; the rest recurses on the pairs.
    const __m256i bit = _mm256_set1_epi16(1);
    const __m256i odd = _mm256_cmpeq_epi16(_mm256_and_si256(r, bit), bit);
    Vecs<(N + 1) / 2> half;
    for (int i = 0; i < N / 2; ++i)
      half[i] = _mm256_blendv_epi8(s[2 * i], s[2 * i + 1], odd);
    if constexpr (N % 2) half[N / 2] = s[N - 1];
    return selectRank<(N + 1) / 2>(half, _mm256_srai_epi16(r, 1));
  }
}

// Scratch rows, each `length` int16 wide; column index c is image column c - h.
template <int K>
class Scratch {
 public:
  static constexpr int kH = K / 2;

  HOROPTER_AVX2_TARGET Scratch(int width, int height) : width_(width), height_(height) {
    blocks_ = (width + kLanes - 1) / kLanes;
    // Whole 64-byte lines per scratch row, so its vector stores never split a line.
    length_ = (blocks_ * kLanes + 2 * kLanes + 31) / 32 * 32;
    const int rows = 2 * K + 2 + K + 1 + (K == 5 ? 2 * K : 0);
    buffer_.assign(static_cast<std::size_t>(rows) * length_ + 32, 0);
    const auto misalign = reinterpret_cast<std::uintptr_t>(buffer_.data()) % 64;
    data_ = buffer_.data() + (misalign ? (64 - misalign) / 2 : 0);
    std::fill(rowPtr(emptyValues()), rowPtr(emptyValues()) + length_, kMax);
    for (int s = 0; s < K; ++s) {
      std::fill(rowPtr(values(s)), rowPtr(values(s)) + length_, kMax);
      slotRow_[s] = -1;
    }
  }

  HOROPTER_AVX2_TARGET void run(const ConstImageView& src, const ImageView& dst, int minValid,
                                std::int16_t invalid, RowRange rows) {
    for (int y = rows.begin; y < rows.end; ++y) {
      std::array<const std::int16_t*, K> val, flag;
      for (int j = 0; j < K; ++j) {
        const int r = y - kH + j;
        if (r < 0 || r >= height_) {
          val[j] = rowPtr(emptyValues());
          flag[j] = rowPtr(emptyFlags());
        } else {
          const int s = r % K;
          if (slotRow_[s] != r) convert(src.row<std::int16_t>(r), invalid, s);
          slotRow_[s] = r;
          val[j] = rowPtr(values(s));
          flag[j] = rowPtr(flags(s));
        }
      }
      sortColumns(val, flag);
      if constexpr (K == 5) mergePairs();
      outputRow(flag[kH], dst.row<std::int16_t>(y), minValid, invalid);
    }
  }

 private:
  // Row indices inside the scratch.
  static constexpr int values(int s) { return s; }
  static constexpr int flags(int s) { return K + s; }
  static constexpr int emptyValues() { return 2 * K; }
  static constexpr int emptyFlags() { return 2 * K + 1; }
  static constexpr int column(int rank) { return 2 * K + 2 + rank; }
  static constexpr int count() { return 3 * K + 2; }
  static constexpr int pair(int rank) { return 3 * K + 3 + rank; }

  // Scratch row addresses held in locals: stores through __m256i may alias
  // anything, so member fields would be reloaded after every store.
  struct Rows {
    std::int16_t* base;
    std::ptrdiff_t length;
    HOROPTER_INLINE std::int16_t* operator()(int i) const { return base + i * length; }
  };
  HOROPTER_AVX2_TARGET Rows rows() { return {data_, length_}; }

  HOROPTER_INLINE std::int16_t* rowPtr(int i) {
    return data_ + static_cast<std::size_t>(i) * length_;
  }

  // values = in[x] or INT16_MAX where invalid, flags = 1 where valid; the
  // padding columns keep INT16_MAX and 0.
  HOROPTER_AVX2_TARGET void convert(const std::int16_t* in, std::int16_t invalid, int s) {
    std::int16_t* val = rowPtr(values(s)) + kH;
    std::int16_t* flag = rowPtr(flags(s)) + kH;
    if (width_ < kLanes) {
      for (int x = 0; x < width_; ++x) {
        val[x] = in[x] == invalid ? kMax : in[x];
        flag[x] = in[x] == invalid ? 0 : 1;
      }
      return;
    }
    const __m256i inv = _mm256_set1_epi16(invalid);
    const __m256i one = _mm256_set1_epi16(1);
    const __m256i maxV = _mm256_set1_epi16(kMax);
    for (int x = 0;; x += kLanes) {
      x = std::min(x, width_ - kLanes);  // the last vector overlaps, writing the same values
      const __m256i v = load(in + x);
      const __m256i bad = _mm256_cmpeq_epi16(v, inv);
      store(val + x, _mm256_blendv_epi8(v, maxV, bad));
      store(flag + x, _mm256_andnot_si256(bad, one));
      if (x == width_ - kLanes) break;
    }
  }

  HOROPTER_AVX2_TARGET void sortColumns(const std::array<const std::int16_t*, K>& val,
                                        const std::array<const std::int16_t*, K>& flag) {
    const Rows row = rows();
    for (int c = 0; c < row.length; c += kLanes) {
      Vecs<K> v;
      __m256i n = _mm256_setzero_si256();
      for (int j = 0; j < K; ++j) {
        v[j] = load(val[j] + c);
        n = _mm256_add_epi16(n, load(flag[j] + c));
      }
      const Vecs<K> sorted = sortNetwork<K>(v);
      for (int j = 0; j < K; ++j)
        store(row(column(j)) + c, sorted[j]);
      store(row(count()) + c, n);
    }
  }

  static HOROPTER_INLINE Vecs<K> loadColumn(const Rows& row, int c) {
    Vecs<K> v;
    for (int j = 0; j < K; ++j)
      v[j] = load(row(column(j)) + c);
    return v;
  }

  // pair(c) = merge(column c, column c + 1).
  HOROPTER_AVX2_TARGET void mergePairs() {
    const Rows row = rows();
    for (int c = 0; c < row.length - kLanes; c += kLanes) {
      const Vecs<2 * K> p = merge<K, K>(loadColumn(row, c), loadColumn(row, c + 1));
      for (int j = 0; j < 2 * K; ++j)
        store(row(pair(j)) + c, p[j]);
    }
  }

  static constexpr int kRanks = (K * K + 1) / 2;

  // The lowest kRanks ranks of the window whose left column is c.
  static HOROPTER_INLINE Vecs<kRanks> window(const Rows& row, int c) {
    Vecs<kRanks> low;
    if constexpr (K == 3) {
      const Vecs<9> all = merge<6, 3>(merge<3, 3>(loadColumn(row, c), loadColumn(row, c + 1)),
                                      loadColumn(row, c + 2));
      for (int j = 0; j < kRanks; ++j)
        low[j] = all[j];
    } else {
      Vecs<10> left, right;
      for (int j = 0; j < 10; ++j) {
        left[j] = load(row(pair(j)) + c);
        right[j] = load(row(pair(j)) + c + 2);
      }
      const Vecs<20> four = merge<10, 10>(left, right);
      // Only the lowest 13 of these 20 can be among the lowest 13 of all 25.
      Vecs<kRanks> fourLow;
      for (int j = 0; j < kRanks; ++j)
        fourLow[j] = four[j];
      const Vecs<kRanks + K> all = merge<kRanks, K>(fourLow, loadColumn(row, c + 4));
      for (int j = 0; j < kRanks; ++j)
        low[j] = all[j];
    }
    return low;
  }

  HOROPTER_AVX2_TARGET void outputRow(const std::int16_t* centreFlag, std::int16_t* out,
                                      int minValid, std::int16_t invalid) {
    const Rows row = rows();
    const int width = width_;
    const int blocks = blocks_;
    const std::int16_t* cnt = row(count());
    const __m256i one = _mm256_set1_epi16(1);
    const __m256i minValidLess1 = _mm256_set1_epi16(static_cast<std::int16_t>(minValid - 1));
    const __m256i inv = _mm256_set1_epi16(invalid);
    const __m256i full = _mm256_set1_epi16(K * K);
    for (int b = 0; b < blocks; ++b) {
      const int x = b * kLanes;
      __m256i n = load(cnt + x);
      for (int j = 1; j < K; ++j)
        n = _mm256_add_epi16(n, load(cnt + x + j));
      // Fast paths: a fully valid block needs only the middle rank (the
      // compiler prunes the merges to its comparators); an empty one is v.
      __m256i median;
      if (_mm256_movemask_epi8(_mm256_cmpeq_epi16(n, full)) == -1) {
        median = window(row, x)[kRanks - 1];
      } else if (_mm256_testz_si256(n, n)) {
        median = inv;
      } else {
        const __m256i rank = _mm256_srai_epi16(_mm256_sub_epi16(n, one), 1);
        median = selectRank<kRanks>(window(row, x), rank);
      }
      const __m256i keep = _mm256_or_si256(_mm256_cmpeq_epi16(load(centreFlag + x + kH), one),
                                           _mm256_cmpgt_epi16(n, minValidLess1));
      const __m256i result = _mm256_blendv_epi8(inv, median, keep);
      if (x + kLanes <= width) {
        store(out + x, result);
      } else {
        alignas(32) std::int16_t tail[kLanes];
        store(tail, result);
        std::memcpy(out + x, tail, sizeof(std::int16_t) * static_cast<std::size_t>(width - x));
      }
    }
  }

  int width_, height_;
  int blocks_ = 0, length_ = 0;
  std::array<int, K> slotRow_{};
  std::vector<std::int16_t> buffer_;
  std::int16_t* data_ = nullptr;  // buffer_'s first 64-byte aligned element
};

}  // namespace

HOROPTER_AVX2_TARGET void medianFilter(const ConstImageView& src, const ImageView& dst,
                                       int kernelSize, int minValid, std::int16_t invalid,
                                       RowRange rows) {
  if (rows.begin >= rows.end) return;
  if (kernelSize == 3) {
    Scratch<3>(src.width, src.height).run(src, dst, minValid, invalid, rows);
  } else {
    Scratch<5>(src.width, src.height).run(src, dst, minValid, invalid, rows);
  }
}

}  // namespace horopter::avx2

#undef HOROPTER_INLINE
