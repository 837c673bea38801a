// The AVX2 kernels of tool rotation (rotation_kernels.h): eight samples,
// rows or lines per instruction, in the same fixed-point and float
// arithmetic as rotation_kernels_scalar.cpp, so results are identical.
//
// Each function carries __attribute__((target("avx2"))) and kernels() calls
// them only on a CPU with AVX2. The file is not compiled with -mavx2, which
// could leave AVX2 copies of inline functions shared with other files for
// the linker to pick; nor are they ifunc or target_clones, on which
// ThreadSanitizer crashes. Elsewhere than x86-64 the file is empty.

#include "tool/rotation_kernels.h"

#ifdef SCULPT_ROTATION_AVX2

#include <immintrin.h>

#include <algorithm>
#include <cstring>

namespace sculpt::core::rotation {
namespace {

__attribute__((target("avx2"), always_inline)) inline __m256i load(const int32_t* p) {
  return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
}
__attribute__((target("avx2"), always_inline)) inline void store(int32_t* p, __m256i v) {
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), v);
}

// The corners of cells i and j, in that order.
__attribute__((target("avx2"), always_inline)) inline __m128i corner_pair(const uint64_t* corners,
                                                                          int32_t i, int32_t j) {
  const __m128i lo = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(corners + i));
  return _mm_insert_epi64(lo, static_cast<long long>(corners[j]), 1);
}

// Eight samples at a time. Takes a batch of lines so the constants are set
// up once: a small tool's lines are short, and a per-line setup cost more
// than their samples. The vector computes the 8 cell indices; the loads are
// scalar: on AMD Zen 4 (this project's machines) AVX2 gathers cost more
// than the loads they replace, the 64-bit gathers of the trilinear corners
// most of all.
__attribute__((target("avx2"))) void sample_lines_avx2(const PreparedTool& tool, Sampling sampling,
                                                       const int32_t step_i[3], const Lines& lines,
                                                       const uint8_t* end) {
  const uint8_t* padded = tool.padded();
  const uint64_t* corners = tool.corners();
  const glm::ivec3 pd = tool.padded_dims();
  const bool nearest = sampling == Sampling::kNearest;
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  __m256i lane_step[3];
  __m256i step8[3];
  for (int i = 0; i < 3; ++i) {
    lane_step[i] = _mm256_mullo_epi32(lane, _mm256_set1_epi32(step_i[i]));
    step8[i] = _mm256_set1_epi32(8 * step_i[i]);
  }
  const __m256i vpx = _mm256_set1_epi32(pd.x);
  const __m256i vpxy = _mm256_set1_epi32(pd.x * pd.y);
  const __m256i even = _mm256_set1_epi32(0x00FF00FF);
  // A face's odd bytes as 16-bit words (one shuffle, not a shift and a mask).
  const __m256i odd = _mm256_setr_epi8(1, -1, 3, -1, 5, -1, 7, -1, 9, -1, 11, -1, 13, -1, 15, -1, 1,
                                       -1, 3, -1, 5, -1, 7, -1, 9, -1, 11, -1, 13, -1, 15, -1);
  const __m256i v256 = _mm256_set1_epi32(256), half = _mm256_set1_epi32(1 << 23);
  // Byte shuffles: a coordinate's fraction (bits 8-15) to bits 0-7 and to
  // bits 16-23 of its lane (one instruction each instead of a shift and a
  // mask), and each lane's low byte to the low 4 bytes of its half.
  const __m256i fraction =
      _mm256_setr_epi8(1, -1, -1, -1, 5, -1, -1, -1, 9, -1, -1, -1, 13, -1, -1, -1, 1, -1, -1, -1,
                       5, -1, -1, -1, 9, -1, -1, -1, 13, -1, -1, -1);
  const __m256i fraction_hi =
      _mm256_setr_epi8(-1, -1, 1, -1, -1, -1, 5, -1, -1, -1, 9, -1, -1, -1, 13, -1, -1, -1, 1, -1,
                       -1, -1, 5, -1, -1, -1, 9, -1, -1, -1, 13, -1);
  const __m256i low_bytes =
      _mm256_setr_epi8(0, 4, 8, 12, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, 0, 4, 8, 12, -1,
                       -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1);
  const __m256i halves = _mm256_setr_epi32(0, 4, 0, 0, 0, 0, 0, 0);
  for (int l = 0; l < lines.count; ++l) {
    const int n = lines.n[l];
    uint8_t* out = lines.out[l];
    __m256i sv[3] = {_mm256_add_epi32(_mm256_set1_epi32(lines.s0[l]), lane_step[0]),
                     _mm256_add_epi32(_mm256_set1_epi32(lines.s1[l]), lane_step[1]),
                     _mm256_add_epi32(_mm256_set1_epi32(lines.s2[l]), lane_step[2])};
    for (int done = 0; done < n; done += 8) {
      // The last group may be partial: its idle lanes read cell 0 (so no
      // read outside the grid) and are not stored.
      const int active = std::min(8, n - done);
      const __m256i ix = _mm256_srai_epi32(sv[0], kFracBits);
      const __m256i iy = _mm256_srai_epi32(sv[1], kFracBits);
      const __m256i iz = _mm256_srai_epi32(sv[2], kFracBits);
      // Two independent products (not (z py + y) px): half the latency.
      __m256i idx = _mm256_add_epi32(
          _mm256_add_epi32(_mm256_mullo_epi32(iz, vpxy), _mm256_mullo_epi32(iy, vpx)), ix);
      if (active < 8)
        idx = _mm256_and_si256(idx, _mm256_cmpgt_epi32(_mm256_set1_epi32(active), lane));
      alignas(32) int32_t cell[8];
      _mm256_store_si256(reinterpret_cast<__m256i*>(cell), idx);
      // The indices are read back from memory, one load each: left to
      // itself the compiler extracts them from the vector (two micro-ops
      // each on Zen 4), which made the trilinear kernel slower.
      asm("" : "+m"(cell));
      if (nearest) {
        for (int j = 0; j < active; ++j)
          out[done + j] = padded[cell[j]];
        for (int i = 0; i < 3; ++i)
          sv[i] = _mm256_add_epi32(sv[i], step8[i]);
        continue;
      }
      // A cell's 8 corners are one 64-bit load. The low half of a takes
      // samples 0, 1, its high half 4, 5; b likewise 2, 3 and 6, 7. The
      // shuffles then split them into the faces at z (low 32 bits) and
      // z + 1 with the samples in order, no lane crossing needed.
      const __m256i a =
          _mm256_inserti128_si256(_mm256_castsi128_si256(corner_pair(corners, cell[0], cell[1])),
                                  corner_pair(corners, cell[4], cell[5]), 1);
      const __m256i b =
          _mm256_inserti128_si256(_mm256_castsi128_si256(corner_pair(corners, cell[2], cell[3])),
                                  corner_pair(corners, cell[6], cell[7]), 1);
      const __m256 af = _mm256_castsi256_ps(a), bf = _mm256_castsi256_ps(b);
      const __m256i fa = _mm256_castps_si256(_mm256_shuffle_ps(af, bf, _MM_SHUFFLE(2, 0, 2, 0)));
      const __m256i fc = _mm256_castps_si256(_mm256_shuffle_ps(af, bf, _MM_SHUFFLE(3, 1, 3, 1)));
      // The x step in 16-bit pairs: a face's even bytes are the two x
      // corners at y, its odd bytes those at y + 1 (see corners()), and
      // one multiply-add per pair gives p(x) (256 - fx) + p(x+1) fx.
      const __m256i fx = _mm256_shuffle_epi8(sv[0], fraction);
      const __m256i wx =
          _mm256_or_si256(_mm256_sub_epi32(v256, fx), _mm256_shuffle_epi8(sv[0], fraction_hi));
      const __m256i c00 = _mm256_madd_epi16(_mm256_and_si256(fa, even), wx);
      const __m256i c10 = _mm256_madd_epi16(_mm256_shuffle_epi8(fa, odd), wx);
      const __m256i c01 = _mm256_madd_epi16(_mm256_and_si256(fc, even), wx);
      const __m256i c11 = _mm256_madd_epi16(_mm256_shuffle_epi8(fc, odd), wx);
      // Along y and z the sums exceed 16 bits: 32-bit products.
      const __m256i fy = _mm256_shuffle_epi8(sv[1], fraction);
      const __m256i gy = _mm256_sub_epi32(v256, fy);
      const __m256i c0 = _mm256_add_epi32(_mm256_mullo_epi32(c00, gy), _mm256_mullo_epi32(c10, fy));
      const __m256i c1 = _mm256_add_epi32(_mm256_mullo_epi32(c01, gy), _mm256_mullo_epi32(c11, fy));
      const __m256i fz = _mm256_shuffle_epi8(sv[2], fraction);
      const __m256i gz = _mm256_sub_epi32(v256, fz);
      const __m256i v = _mm256_srli_epi32(
          _mm256_add_epi32(_mm256_add_epi32(_mm256_mullo_epi32(c0, gz), _mm256_mullo_epi32(c1, fz)),
                           half),
          24);
      const __m256i packed = _mm256_permutevar8x32_epi32(_mm256_shuffle_epi8(v, low_bytes), halves);
      const auto bytes = static_cast<uint64_t>(_mm_cvtsi128_si64(_mm256_castsi256_si128(packed)));
      if (active == 8) {
        std::memcpy(out + done, &bytes, 8);
      } else {
        // A line's last few samples: eight bytes read, the line's merged
        // in, written back (a memcpy of a variable size was a library call
        // per line, and stores by the bits of the count mispredicted). The
        // bytes past the line keep their values; later lines overwrite
        // them as ever. Byte by byte where eight would pass `end`.
        uint8_t* d = out + done;
        if (d + 8 <= end) {
          const uint64_t keep = ~uint64_t{0} << (8 * active);
          uint64_t old;
          std::memcpy(&old, d, 8);
          const uint64_t merged = (old & keep) | (bytes & ~keep);
          std::memcpy(d, &merged, 8);
        } else {
          for (int j = 0; j < active; ++j)
            d[j] = static_cast<uint8_t>(bytes >> (8 * j));
        }
      }
      for (int i = 0; i < 3; ++i)
        sv[i] = _mm256_add_epi32(sv[i], step8[i]);
    }
  }
}

// The float operations of spans_scalar(), eight rows at a time: the same
// IEEE operations per lane, so the same spans. Per row, two square roots
// and four roundings, whose latency one or four rows at a time (SSE) was a
// large share of a small tool's rotation.
__attribute__((target("avx2"), always_inline)) inline __m256 ceil8(__m256 v) {
  const __m256 t = _mm256_cvtepi32_ps(_mm256_cvttps_epi32(v));
  return _mm256_add_ps(t, _mm256_and_ps(_mm256_cmp_ps(t, v, _CMP_LT_OQ), _mm256_set1_ps(1.0f)));
}
__attribute__((target("avx2"), always_inline)) inline __m256 floor8(__m256 v) {
  const __m256 t = _mm256_cvtepi32_ps(_mm256_cvttps_epi32(v));
  return _mm256_sub_ps(t, _mm256_and_ps(_mm256_cmp_ps(t, v, _CMP_GT_OQ), _mm256_set1_ps(1.0f)));
}
__attribute__((target("avx2"), always_inline)) inline __m256 select8(__m256 mask, __m256 a,
                                                                     __m256 b) {
  return _mm256_or_ps(_mm256_and_ps(mask, a), _mm256_andnot_ps(mask, b));
}
__attribute__((target("avx2"), always_inline)) inline void store8(int32_t* out, __m256 v) {
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), _mm256_cvttps_epi32(v));
}

// The runs' rows, in whole eights (the arrays have the slack). All the
// runs of a batch of planes in one loop: a plane's rows alone were too few
// to hide the square roots' latency.
__attribute__((target("avx2"))) void spans_avx2(const float centre[3], float reach2, float core2,
                                                float width, const SpanRun* runs, int count,
                                                Spans& out) {
  const float cz = centre[2];
  const __m256 vcx = _mm256_set1_ps(centre[0]), vcy = _mm256_set1_ps(centre[1]);
  const __m256 vreach2 = _mm256_set1_ps(reach2), vcore2 = _mm256_set1_ps(core2);
  const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f);
  const __m256 vwidth = _mm256_set1_ps(width);
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const bool any_core = core2 > 0.0f;
  for (int r = 0; r < count; ++r) {
    const SpanRun& run = runs[r];
    const float dz = static_cast<float>(run.z) - cz;
    const __m256 vdz2 = _mm256_set1_ps(dz * dz);
    for (int i = 0; i < run.n; i += 8) {
      const int at = run.at + i;
      const __m256 y = _mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_set1_epi32(run.y0 + i), lane));
      const __m256 dy = _mm256_sub_ps(y, vcy);
      const __m256 r2 = _mm256_add_ps(_mm256_mul_ps(dy, dy), vdz2);
      const __m256 h2 = _mm256_sub_ps(vreach2, r2);
      const __m256 h = _mm256_sqrt_ps(_mm256_max_ps(h2, zero));
      __m256 x0 = _mm256_max_ps(zero, ceil8(_mm256_sub_ps(vcx, h)));
      __m256 x1 = _mm256_min_ps(vwidth, _mm256_add_ps(floor8(_mm256_add_ps(vcx, h)), one));
      const __m256 hit =
          _mm256_and_ps(_mm256_cmp_ps(h2, zero, _CMP_GE_OQ), _mm256_cmp_ps(x0, x1, _CMP_LT_OQ));
      x0 = _mm256_and_ps(hit, x0);
      x1 = _mm256_and_ps(hit, x1);
      const __m256 k2 = _mm256_sub_ps(vcore2, r2);
      const __m256 k = _mm256_sqrt_ps(_mm256_max_ps(k2, zero));
      const __m256 has_core = any_core ? _mm256_cmp_ps(k2, zero, _CMP_GT_OQ) : _mm256_setzero_ps();
      const __m256 c0 =
          select8(has_core, _mm256_min_ps(_mm256_max_ps(ceil8(_mm256_sub_ps(vcx, k)), x0), x1), x1);
      const __m256 c1 = select8(
          has_core,
          _mm256_min_ps(_mm256_max_ps(_mm256_add_ps(floor8(_mm256_add_ps(vcx, k)), one), c0), x1),
          x1);
      store8(out.x0 + at, x0);
      store8(out.x1 + at, x1);
      store8(out.c0 + at, c0);
      store8(out.c1 + at, c1);
    }
  }
}

// Lines k .. k + 7 of `lines`, one per row of eight: row r's starts at x
// offset start[r] with n[r] samples, its first sample at row_s + r J +
// start I and its output at out + r width + start.
__attribute__((target("avx2"), always_inline)) inline void put_lines(
    Lines& lines, int k, const int32_t row_s[3], const int32_t step_i[3], const int32_t step_j[3],
    __m256i start, __m256i n, int width, uint8_t* out) {
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  int32_t* const s[3] = {lines.s0 + k, lines.s1 + k, lines.s2 + k};
  for (int i = 0; i < 3; ++i)
    store(s[i],
          _mm256_add_epi32(_mm256_add_epi32(_mm256_set1_epi32(row_s[i]),
                                            _mm256_mullo_epi32(lane, _mm256_set1_epi32(step_j[i]))),
                           _mm256_mullo_epi32(start, _mm256_set1_epi32(step_i[i]))));
  store(lines.n + k, n);
  const __m256i offset =
      _mm256_add_epi32(_mm256_mullo_epi32(lane, _mm256_set1_epi32(width)), start);
  const __m256i base = _mm256_set1_epi64x(reinterpret_cast<int64_t>(out));
  store(reinterpret_cast<int32_t*>(lines.out + k),
        _mm256_add_epi64(base, _mm256_cvtepi32_epi64(_mm256_castsi256_si128(offset))));
  store(reinterpret_cast<int32_t*>(lines.out + k + 4),
        _mm256_add_epi64(base, _mm256_cvtepi32_epi64(_mm256_extracti128_si256(offset, 1))));
}

// plan_row() for eight whole rows at once (no clipping to the support), in
// the same integer arithmetic, so the same lines and fills. Rows that miss
// the reach ball, and the right-hand side of rows whose core is sampled,
// become lines of no samples rather than branches: planning row by row was
// a large share of a small tool's rotation.
__attribute__((target("avx2"))) void plan_rows_avx2(const int32_t row_s[3], const int32_t step_i[3],
                                                    const int32_t step_j[3], int width,
                                                    uint8_t core_value, const Spans& sp, int i,
                                                    int m, uint8_t* out, Lines& lines) {
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i x0 = load(sp.x0 + i), x1 = load(sp.x1 + i);
  const __m256i c0 = _mm256_min_epi32(_mm256_max_epi32(load(sp.c0 + i), x0), x1);
  const __m256i c1 = _mm256_min_epi32(_mm256_max_epi32(load(sp.c1 + i), c0), x1);
  const __m256i hit = _mm256_cmpgt_epi32(x1, x0);
  const __m256i rows = _mm256_cmpgt_epi32(_mm256_set1_epi32(m), lane);
  const __m256i filled = _mm256_and_si256(
      _mm256_and_si256(hit, rows),
      _mm256_cmpgt_epi32(_mm256_sub_epi32(c1, c0), _mm256_set1_epi32(kMinCoreRun - 1)));
  const int k = lines.count;
  if (_mm256_testz_si256(filled, filled)) {
    // Every core sampled: one line a row, x0 .. x1.
    put_lines(lines, k, row_s, step_i, step_j, x0, _mm256_and_si256(hit, _mm256_sub_epi32(x1, x0)),
              width, out);
    lines.count = k + m;
    return;
  }
  // x0 .. c0 and c1 .. x1 where the core is filled, x0 .. x1 elsewhere. The
  // right-hand lines overwrite the left-hand ones past row m.
  const __m256i left_end = _mm256_blendv_epi8(x1, c0, filled);
  put_lines(lines, k, row_s, step_i, step_j, x0,
            _mm256_and_si256(hit, _mm256_sub_epi32(left_end, x0)), width, out);
  put_lines(lines, k + m, row_s, step_i, step_j, c1,
            _mm256_and_si256(filled, _mm256_sub_epi32(x1, c1)), width, out);
  lines.count = k + 2 * m;
  if (core_value == 0) return;
  alignas(32) int32_t from[8], to[8];
  store(from, c0);
  store(to, c1);
  for (int mask = _mm256_movemask_ps(_mm256_castsi256_ps(filled)); mask != 0; mask &= mask - 1) {
    const int r = __builtin_ctz(static_cast<unsigned>(mask));
    std::memset(out + static_cast<size_t>(r) * width + from[r], core_value, to[r] - from[r]);
  }
}

}  // namespace

const Kernels kAvx2Kernels = {sample_lines_avx2, spans_avx2, plan_rows_avx2};

}  // namespace sculpt::core::rotation

#endif  // SCULPT_ROTATION_AVX2
