// Rows are short (a brick is 32 voxels wide, and a dab's rows are clipped to
// the tool's reach), so an auto-vectorised loop spends most of a row in its
// scalar epilogue. The AVX2 kernel instead covers any row of up to 32 voxels
// with one 32-byte step: it reads past the row's end (the callers' buffers
// have kCombineRowSlack bytes of slack) and blends the original bytes back
// there before storing. At full strength (q = 256) the filling is the tool
// value itself, and add, subtract, union and difference are single
// saturating byte instructions.

#include "sculpt/core/sculpt/combine_row.h"

#include <algorithm>
#include <cassert>

#include "cpu_has_avx2.h"
#include "sculpt/core/sculpt/sculptor.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define SCULPT_COMBINE_AVX2 1
#endif

namespace sculpt::core {
namespace {

// Every intermediate fits 16 bits (f q + 128 <= 255 * 256 + 128, sums <= 510).
template <class Op>
int64_t combine(uint8_t* m, const uint8_t* f, int n, uint32_t q32, Op op) {
  const auto q = static_cast<uint16_t>(q32);
  int64_t changed = 0;
  for (int i = 0; i < n; ++i) {
    const uint16_t v = m[i];
    const auto a = static_cast<uint16_t>(static_cast<uint16_t>(f[i] * q + 128) >> 8);
    const uint16_t r = op(v, a);
    changed += r != v;
    m[i] = static_cast<uint8_t>(r);
  }
  return changed;
}

#ifdef SCULPT_COMBINE_AVX2
template <SculptMode kMode>
__attribute__((target("avx2,popcnt"))) int64_t combine_avx2(uint8_t* m, const uint8_t* f, int n,
                                                            uint32_t q) {
  const __m256i lane = _mm256_setr_epi8(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16,
                                        17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31);
  const __m256i zero = _mm256_setzero_si256();
  const __m256i vq = _mm256_set1_epi16(static_cast<int16_t>(q));
  const __m256i round = _mm256_set1_epi16(128);
  int64_t changed = 0;
  for (int i = 0; i < n; i += 32) {
    const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(m + i));
    __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(f + i));
    if (q != 256) {
      // (f q + 128) >> 8 on 16-bit lanes; unpack and pack pair up the same
      // 128-bit halves, so the byte order is kept.
      __m256i lo = _mm256_unpacklo_epi8(a, zero), hi = _mm256_unpackhi_epi8(a, zero);
      lo = _mm256_srli_epi16(_mm256_add_epi16(_mm256_mullo_epi16(lo, vq), round), 8);
      hi = _mm256_srli_epi16(_mm256_add_epi16(_mm256_mullo_epi16(hi, vq), round), 8);
      a = _mm256_packus_epi16(lo, hi);
    }
    __m256i r;
    if constexpr (kMode == SculptMode::kAdd) {
      r = _mm256_adds_epu8(v, a);
    } else if constexpr (kMode == SculptMode::kSubtract) {
      r = _mm256_subs_epu8(v, a);
    } else if constexpr (kMode == SculptMode::kUnion) {
      r = _mm256_max_epu8(v, a);
    } else {
      r = _mm256_min_epu8(v, _mm256_xor_si256(a, _mm256_set1_epi32(-1)));
    }
    // Lanes past the row's end keep their bytes.
    const __m256i inside =
        _mm256_cmpgt_epi8(_mm256_set1_epi8(static_cast<char>(std::min(32, n - i))), lane);
    r = _mm256_blendv_epi8(v, r, inside);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(m + i), r);
    const auto same = static_cast<uint32_t>(_mm256_movemask_epi8(_mm256_cmpeq_epi8(r, v)));
    changed += __builtin_popcount(~same);
  }
  return changed;
}

#endif

}  // namespace

int64_t combine_row_scalar(SculptMode mode, uint8_t* m, const uint8_t* f, int n, uint32_t q) {
  assert(q <= 256);
  using U = uint16_t;
  switch (mode) {
    case SculptMode::kAdd:
      return combine(m, f, n, q, [](U v, U a) { return static_cast<U>(std::min<U>(255, v + a)); });
    case SculptMode::kSubtract:
      return combine(m, f, n, q, [](U v, U a) { return static_cast<U>(v > a ? v - a : 0); });
    case SculptMode::kUnion:
      return combine(m, f, n, q, [](U v, U a) { return std::max(v, a); });
    case SculptMode::kDifference:
      return combine(m, f, n, q, [](U v, U a) { return std::min<U>(v, static_cast<U>(255 - a)); });
    case SculptMode::kSmooth:
      break;
  }
  assert(false && "combine_row(): smoothing has its own kernel");
  return 0;
}

int64_t combine_row(SculptMode mode, uint8_t* m, const uint8_t* f, int n, uint32_t q) {
  assert(q <= 256);
#ifdef SCULPT_COMBINE_AVX2
  if (cpu_has_avx2()) {
    switch (mode) {
      case SculptMode::kAdd:
        return combine_avx2<SculptMode::kAdd>(m, f, n, q);
      case SculptMode::kSubtract:
        return combine_avx2<SculptMode::kSubtract>(m, f, n, q);
      case SculptMode::kUnion:
        return combine_avx2<SculptMode::kUnion>(m, f, n, q);
      case SculptMode::kDifference:
        return combine_avx2<SculptMode::kDifference>(m, f, n, q);
      case SculptMode::kSmooth:
        break;
    }
  }
#endif
  return combine_row_scalar(mode, m, f, n, q);
}

}  // namespace sculpt::core
