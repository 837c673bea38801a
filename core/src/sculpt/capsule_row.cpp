// Where a capsule crosses the rows of a plane (capsule_rows()), and the hard
// ball's stroke row kernel (capsule_row.h). A segment adds to each
// row it crosses a few voxels (the benchmark's stroke: 9 a row on average),
// so the auto-vectorised loop of hard_capsule_filling() spent most of a row
// in its prologue and scalar epilogue, and finding where the coverage grew
// and raising it took two more passes. The AVX2 kernel covers a brick row of
// up to 32 voxels in one step: the fillings of the 8-voxel groups that meet
// [lo, hi), packed to bytes, masked to [lo, hi), raised into the coverage
// with one byte max, and the grown stretch read from one compare mask.
//
// The floats are hard_capsule_filling()'s, operation for operation (no FMA:
// the target is "avx2" alone, so nothing is contracted), and min/max differ
// from std::min/std::max only in the sign of a zero or a NaN: neither occurs
// in a byte here (t's zero is squared away, f's converts to 0).

#include "sculpt/core/sculpt/capsule_row.h"

#include "cpu_has_avx2.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define SCULPT_CAPSULE_AVX2 1
#endif

namespace sculpt::core {
namespace {

// capsule_rows()'s cylinder part, one loop per case with no branch in it
// (GCC vectorizes no loop with one): a miss is an empty [c0, c1]. The
// segment's start a, its vector ab, ab2 = |ab|^2.
template <bool kAcrossX, bool kSolvable>
void cylinder_rows(glm::vec3 a, glm::vec3 ab, float ab2, int y0, int n, float z, float rho2,
                   float* __restrict lo, float* __restrict hi) {
  constexpr float kFar = 1e30f;
  const float aa = 1.0f - ab.x * ab.x / ab2;
  const float m2abx = -2.0f * ab.x, aa4 = 4.0f * aa, aa2 = 2.0f * aa;
  const float wz = z - a.z;
  for (int i = 0; i < n; ++i) {
    const float wy = static_cast<float>(y0 + i) - a.y;
    const float k = wy * ab.y + wz * ab.z;
    float t0 = -kFar, t1 = kFar;
    if constexpr (kAcrossX) {
      const float p = -k / ab.x, q = (ab2 - k) / ab.x;
      t0 = std::min(p, q);
      t1 = std::max(p, q);
    } else {
      const bool within = (k >= 0.0f) & (k <= ab2);
      t0 = within ? t0 : kFar;
      t1 = within ? t1 : -kFar;
    }
    float p0 = -kFar, p1 = kFar;
    if constexpr (kSolvable) {
      const float bb = m2abx * k / ab2;
      const float cc = wy * wy + wz * wz - k * k / ab2 - rho2;
      const float disc = bb * bb - aa4 * cc;
      const float r = std::sqrt(std::max(disc, 0.0f));
      p0 = (-bb - r) / aa2;
      p1 = (-bb + r) / aa2;
      p0 = disc >= 0.0f ? p0 : kFar;
    }
    const float c0 = std::max(t0, p0), c1 = std::min(t1, p1);
    // A miss moves the stretch out of reach of the hull (adding 0 changes
    // no float); a select of the results instead keeps GCC from vectorizing.
    const float miss = c0 <= c1 ? 0.0f : kFar;
    lo[i] = std::min(lo[i], a.x + c0 + miss);
    hi[i] = std::max(hi[i], a.x + c1 - miss);
  }
}

#ifdef SCULPT_CAPSULE_AVX2
__attribute__((target("avx2"))) GrownStretch grow_avx2(const CapsuleRow& c, int x0, int lo, int hi,
                                                       uint8_t* cov, int in_lo, int in_hi) {
  const __m256 a_x = _mm256_set1_ps(c.a_x);
  const __m256 abx = _mm256_set1_ps(c.ab.x), aby = _mm256_set1_ps(c.ab.y);
  const __m256 abz = _mm256_set1_ps(c.ab.z);
  const __m256 dot_yz = _mm256_set1_ps(c.dot_yz), inv_ab2 = _mm256_set1_ps(c.inv_ab2);
  const __m256 apy = _mm256_set1_ps(c.apy), apz = _mm256_set1_ps(c.apz);
  const __m256 radius = _mm256_set1_ps(c.radius);
  const __m256 inner2 = _mm256_set1_ps(c.inner2), reach2 = _mm256_set1_ps(c.reach2);
  const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f);
  const __m256 half_step = _mm256_set1_ps(127.5f), f255 = _mm256_set1_ps(255.0f);
  const __m256i lane8 = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  // The four 8-voxel groups' fillings as 32-bit integers (0 where unmet).
  __m256i group[4] = {_mm256_setzero_si256(), _mm256_setzero_si256(), _mm256_setzero_si256(),
                      _mm256_setzero_si256()};
  // Groups whose 8 voxels the stroke filled fully already cannot grow: no
  // filling is computed for them (their 0 leaves the coverage as it is).
  const __m256i before = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(cov));
  const auto full = static_cast<uint32_t>(
      _mm256_movemask_epi8(_mm256_cmpeq_epi8(before, _mm256_set1_epi8(static_cast<char>(-1)))));
  for (int g = lo >> 3; g <= (hi - 1) >> 3; ++g) {
    if (((full >> (8 * g)) & 0xFFu) == 0xFFu) continue;
    if (8 * g >= in_lo && 8 * g + 8 <= in_hi) {  // inside radius - 1: 255, unmeasured
      group[g] = _mm256_set1_epi32(255);
      continue;
    }
    const __m256i x = _mm256_add_epi32(_mm256_set1_epi32(x0 + 8 * g), lane8);
    const __m256 apx = _mm256_sub_ps(_mm256_cvtepi32_ps(x), a_x);
    __m256 t = _mm256_mul_ps(_mm256_add_ps(_mm256_mul_ps(apx, abx), dot_yz), inv_ab2);
    t = _mm256_min_ps(_mm256_max_ps(t, zero), one);
    const __m256 dx = _mm256_sub_ps(apx, _mm256_mul_ps(t, abx));
    const __m256 dy = _mm256_sub_ps(apy, _mm256_mul_ps(t, aby));
    const __m256 dz = _mm256_sub_ps(apz, _mm256_mul_ps(t, abz));
    const __m256 d2 = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)),
                                    _mm256_mul_ps(dz, dz));
    const __m256 d = _mm256_sub_ps(_mm256_sqrt_ps(d2), radius);
    __m256 f = _mm256_sub_ps(half_step, _mm256_mul_ps(d, half_step));
    f = _mm256_min_ps(_mm256_max_ps(f, zero), f255);
    f = _mm256_blendv_ps(f255, f, _mm256_cmp_ps(d2, inner2, _CMP_GT_OQ));
    f = _mm256_blendv_ps(zero, f, _mm256_cmp_ps(d2, reach2, _CMP_LT_OQ));
    group[g] = _mm256_cvttps_epi32(f);
  }
  // Packing works within 128-bit halves: the bytes come out as the groups'
  // 4-voxel quarters interleaved (0a 1a 2a 3a 0b 1b 2b 3b), put back in order.
  const __m256i words01 = _mm256_packus_epi32(group[0], group[1]);
  const __m256i words23 = _mm256_packus_epi32(group[2], group[3]);
  const __m256i bytes = _mm256_permutevar8x32_epi32(_mm256_packus_epi16(words01, words23),
                                                    _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7));
  const __m256i lane = _mm256_setr_epi8(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16,
                                        17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31);
  const __m256i inside =
      _mm256_and_si256(_mm256_cmpgt_epi8(lane, _mm256_set1_epi8(static_cast<char>(lo - 1))),
                       _mm256_cmpgt_epi8(_mm256_set1_epi8(static_cast<char>(hi)), lane));
  const __m256i fill = _mm256_and_si256(bytes, inside);
  const __m256i after = _mm256_max_epu8(before, fill);
  const auto grew = ~static_cast<uint32_t>(_mm256_movemask_epi8(_mm256_cmpeq_epi8(after, before)));
  if (grew == 0) return {};
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(cov), after);
  return {__builtin_ctz(grew), 32 - __builtin_clz(grew)};
}
#endif

}  // namespace

// The capsule is convex, so a row's stretch is the hull of its end balls'
// stretches and its cylinder's (perpendicular distance, a quadratic in x,
// with the projection inside the segment, linear in x). The rows of a plane
// are solved at once: the segment's cases are decided once and none per row,
// so that the loops run a vector at a time. (Solved a row at a time, with
// early returns, the spans took 2 of the 11 ms of BM_StrokeVsDabs's stroke at
// spacing 8; these are the same floats, checked row by row against that
// solver on the benchmark and the bundled sessions when it was replaced.)
void capsule_rows(glm::vec3 a, glm::vec3 ab, float ab2, int y0, int n, float z, float rho2,
                  bool outer, float* __restrict lo, float* __restrict hi) {
  constexpr float kFar = 1e30f;
  const glm::vec3 b = a + ab;
  const float dza2 = (z - a.z) * (z - a.z), dzb2 = (z - b.z) * (z - b.z);
  // The end balls' hull.
  for (int i = 0; i < n; ++i) {
    const float y = static_cast<float>(y0 + i);
    const float r2a = rho2 - (y - a.y) * (y - a.y) - dza2;
    const float r2b = rho2 - (y - b.y) * (y - b.y) - dzb2;
    const float sa = std::sqrt(std::max(r2a, 0.0f)), sb = std::sqrt(std::max(r2b, 0.0f));
    float l = r2a >= 0.0f ? a.x - sa : kFar;
    float h = r2a >= 0.0f ? a.x + sa : -kFar;
    l = r2b >= 0.0f ? std::min(l, b.x - sb) : l;
    h = r2b >= 0.0f ? std::max(h, b.x + sb) : h;
    lo[i] = l;
    hi[i] = h;
  }
  if (ab2 <= 0.0f) return;
  // The cylinder's stretch, where the projection lies within the segment.
  const bool across_x = std::abs(ab.x) > 1e-6f * std::sqrt(ab2);
  const float aa = 1.0f - ab.x * ab.x / ab2;
  const bool solvable = aa > 1e-3f;
  if (!solvable && !outer) return;
  if (across_x) {
    solvable ? cylinder_rows<true, true>(a, ab, ab2, y0, n, z, rho2, lo, hi)
             : cylinder_rows<true, false>(a, ab, ab2, y0, n, z, rho2, lo, hi);
  } else {
    solvable ? cylinder_rows<false, true>(a, ab, ab2, y0, n, z, rho2, lo, hi)
             : cylinder_rows<false, false>(a, ab, ab2, y0, n, z, rho2, lo, hi);
  }
}

GrownStretch raise_coverage(const uint8_t* fill, uint8_t* cov, int lo, int hi) {
  int g0 = lo, g1 = hi;
  while (g0 < g1 && fill[g0] <= cov[g0])
    ++g0;
  while (g1 > g0 && fill[g1 - 1] <= cov[g1 - 1])
    --g1;
  for (int x = g0; x < g1; ++x)
    cov[x] = std::max(cov[x], fill[x]);
  return {g0, g1};
}

GrownStretch grow_hard_capsule_row_scalar(const CapsuleRow& c, int x0, int lo, int hi, uint8_t* cov,
                                          uint8_t* fill) {
  for (int x = lo; x < hi; ++x)
    fill[x] = hard_capsule_filling(c, x0 + x);
  return raise_coverage(fill, cov, lo, hi);
}

GrownStretch grow_hard_capsule_row(const CapsuleRow& c, int x0, int lo, int hi, uint8_t* cov,
                                   uint8_t* fill, int in_lo, int in_hi) {
  if (lo >= hi) return {};
#ifdef SCULPT_CAPSULE_AVX2
  if (hi <= 32 && cpu_has_avx2()) return grow_avx2(c, x0, lo, hi, cov, in_lo, in_hi);
#endif
  for (int x = lo; x < hi; ++x)
    fill[x] = x >= in_lo && x < in_hi ? uint8_t{255} : hard_capsule_filling(c, x0 + x);
  return raise_coverage(fill, cov, lo, hi);
}

}  // namespace sculpt::core
