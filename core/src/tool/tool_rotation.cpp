// Discrete tool rotation, "Discrete tools for virtual sculpture" §3.1-3.2.
//
// Departures from the paper's text, all for speed without changing what is
// computed: the map runs in 16.16 fixed point (exact integer stepping, so
// brute force and Algorithm 1 agree bit for bit); each row is clipped to the
// stretch whose samples can be non-zero (the reach ball); the stretch inside
// the tool's core (a ball round the pivot where every sample reads one
// value, 255 inside a solid tool) is filled without sampling; and the scalar
// kernel skips equal-cornered cells (PreparedTool's cell table), so the cost
// follows the tool's surface rather than its rotated box. Rows are planned
// first and sampled in batches. Memory is x fastest, so the innermost step
// is along x (the paper steps along z).

#include "sculpt/core/tool/tool_rotation.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstring>
#include <utility>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace sculpt::core {
namespace {

std::atomic<bool> g_vector_kernel{true};

constexpr int kFracBits = 16;
constexpr double kOne = 1 << kFracBits;
constexpr int kPad = PreparedTool::kPad;
// Core stretches shorter than this are sampled rather than filled.
constexpr int kMinCoreRun = 16;

int32_t to_fixed(double v) {
  return static_cast<int32_t>(std::llround(v * kOne));
}

// Sample coordinates are padded tool voxels; nearest rounds by flooring
// s + 0.5, folded into the coordinate so both samplers floor.
double sample_shift(Sampling sampling) {
  return kPad + (sampling == Sampling::kNearest ? 0.5 : 0.0);
}

// floor and ceil of doubles well inside the int range, inline: the baseline
// x86-64 target has no rounding instruction, and the libm calls cost more
// than a row's samples.
inline double fast_floor(double x) {
  const double t = static_cast<double>(static_cast<int64_t>(x));
  return t > x ? t - 1.0 : t;
}
inline double fast_ceil(double x) {
  const double t = static_cast<double>(static_cast<int64_t>(x));
  return t < x ? t + 1.0 : t;
}

size_t cell_index(const int32_t s[3], glm::ivec3 pd) {
  return (static_cast<size_t>(s[2] >> kFracBits) * pd.y + static_cast<size_t>(s[1] >> kFracBits)) *
             pd.x +
         static_cast<size_t>(s[0] >> kFracBits);
}

// Trilinear sample of cell i with 8-bit weights: each axis' pair sums to 256,
// so an equal-cornered cell returns its value exactly and the 32-bit sum
// cannot overflow (255 * 2^24 + 2^23 < 2^32).
[[gnu::always_inline]] inline uint8_t trilinear_at(const uint8_t* padded, size_t i,
                                                   const int32_t s[3], size_t px, size_t pxy) {
  const uint32_t fx = (static_cast<uint32_t>(s[0]) >> 8) & 255u;
  const uint32_t fy = (static_cast<uint32_t>(s[1]) >> 8) & 255u;
  const uint32_t fz = (static_cast<uint32_t>(s[2]) >> 8) & 255u;
  const uint8_t* p = padded + i;
  const uint32_t c00 = p[0] * (256 - fx) + p[1] * fx;
  const uint32_t c10 = p[px] * (256 - fx) + p[px + 1] * fx;
  const uint32_t c01 = p[pxy] * (256 - fx) + p[pxy + 1] * fx;
  const uint32_t c11 = p[pxy + px] * (256 - fx) + p[pxy + px + 1] * fx;
  const uint32_t c0 = c00 * (256 - fy) + c10 * fy;
  const uint32_t c1 = c01 * (256 - fy) + c11 * fy;
  return static_cast<uint8_t>((c0 * (256 - fz) + c1 * fz + (1u << 23)) >> 24);
}

#if defined(__x86_64__) && defined(__GNUC__)
#define SCULPT_TOOL_AVX2 1
// Eight samples at a time with AVX2 (chosen at run time, so the library
// still runs on any x86-64). Same fixed-point arithmetic as the scalar code,
// so results are identical. Takes a batch of lines so the constants are set
// up once: at 16^3 a line is about 12 samples, and the per-line setup cost
// more than the samples. The vector computes the 8 cell indices; the loads
// are scalar: on AMD Zen 4 (this project's machines) AVX2 gathers cost more
// than the loads they replace, the 64-bit gathers of the trilinear corners
// most of all (scalar loads: nearest 5-10% and trilinear 10-25% faster).
// The corners of cells i and j, in that order.
__attribute__((target("avx2"), always_inline)) inline __m128i corner_pair(const uint64_t* corners,
                                                                          int32_t i, int32_t j) {
  const __m128i lo = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(corners + i));
  return _mm_insert_epi64(lo, static_cast<long long>(corners[j]), 1);
}

__attribute__((target("avx2"))) void sample_lines_avx2(const uint8_t* padded,
                                                       const uint64_t* corners, glm::ivec3 pd,
                                                       const int32_t st[3],
                                                       const RotationFrame::Lines& lines,
                                                       const uint8_t* end, bool nearest) {
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  __m256i lane_step[3];
  __m256i step8[3];
  for (int i = 0; i < 3; ++i) {
    lane_step[i] = _mm256_mullo_epi32(lane, _mm256_set1_epi32(st[i]));
    step8[i] = _mm256_set1_epi32(8 * st[i]);
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
      // each on Zen 4), which made the trilinear kernel 3% slower.
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

bool cpu_has_avx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}
#endif

}  // namespace

glm::mat3 euler_xyz_deg(glm::vec3 degrees) {
  const glm::vec3 r = glm::radians(degrees);
  const glm::mat4 rx = glm::rotate(glm::mat4(1.0f), r.x, glm::vec3(1, 0, 0));
  const glm::mat4 ry = glm::rotate(glm::mat4(1.0f), r.y, glm::vec3(0, 1, 0));
  const glm::mat4 rz = glm::rotate(glm::mat4(1.0f), r.z, glm::vec3(0, 0, 1));
  glm::mat3 m(rz * ry * rx);
  // Quarter turns must be exact: snap float noise (cos 90 deg = -4e-8) to 0.
  for (int c = 0; c < 3; ++c)
    for (int r2 = 0; r2 < 3; ++r2)
      if (std::abs(m[c][r2]) < 1e-6f) m[c][r2] = 0.0f;
  return m;
}

bool use_vector_kernel(bool enabled) {
  g_vector_kernel.store(enabled, std::memory_order_relaxed);
#ifdef SCULPT_TOOL_AVX2
  return enabled && cpu_has_avx2();
#else
  return false;
#endif
}

PreparedTool::PreparedTool(Tool tool) : tool_(std::move(tool)) {
  const glm::ivec3 d = tool_.density.dims();
  const glm::ivec3 pd = d + 2 * kPad;
  padded_dims_ = pd;
  const size_t count = static_cast<size_t>(voxel_count(pd));
  // Slack after the grid, for reads wider than a byte.
  padded_.assign(count + 4, 0);
  const size_t px = pd.x;
  const size_t pxy = px * pd.y;
  // The core value: the voxel nearest the pivot's; no core if that is outside.
  const glm::ivec3 centre(glm::floor(tool_.pivot + 0.5f));
  const bool centred = tool_.density.in_bounds(centre.x, centre.y, centre.z);
  const uint8_t u = centred ? tool_.density.at(centre.x, centre.y, centre.z) : 0;
  // A sample at t reads voxels w with |t_i - w_i| <= m on every axis (m = 0.5
  // nearest, < 1 trilinear): it can be non-zero only within
  // |w - pivot| + m per axis of a non-zero voxel w, and reads only u closer
  // than |w - pivot| - m per axis to every voxel w != u. Per axis, not
  // sqrt(3) m along the radius: a thinner shell left to sample.
  constexpr double kMargin[2] = {0.5, 1.0};
  double reach2[2] = {0.0, 0.0};
  double other2[2] = {centred ? 1e300 : 0.0, centred ? 1e300 : 0.0};
  const glm::dvec3 pivot(tool_.pivot);
  if (u != 0) {
    // Outside the grid reads 0: the layers at -1 and d on each axis.
    for (int i = 0; i < 3; ++i) {
      const double gap = std::min(pivot[i] + 1.0, d[i] - pivot[i]);
      for (int k = 0; k < 2; ++k) {
        const double g = std::max(0.0, gap - kMargin[k]);
        other2[k] = std::min(other2[k], g * g);
      }
    }
  }
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        const uint8_t v = tool_.density.at(x, y, z);
        padded_[(z + kPad) * pxy + (y + kPad) * px + (x + kPad)] = v;
        if (v == 0 && v == u) continue;
        const glm::dvec3 r = glm::abs(glm::dvec3(x, y, z) - pivot);
        for (int k = 0; k < 2; ++k) {
          if (v != 0) {
            const glm::dvec3 far = r + kMargin[k];
            reach2[k] = std::max(reach2[k], glm::dot(far, far));
          }
          if (v != u) {
            const glm::dvec3 near = glm::max(r - kMargin[k], 0.0);
            other2[k] = std::min(other2[k], glm::dot(near, near));
          }
        }
      }
  for (int k = 0; k < 2; ++k) {
    reach_vox_[k] = static_cast<float>(std::sqrt(reach2[k]));
    core_radius_vox_[k] = centred ? static_cast<float>(std::sqrt(other2[k])) : 0.0f;
  }
  core_value_ = u;

  // Cells whose 8 corners are equal: their trilinear sample is that value
  // whatever the weights. The last layer has no +1 neighbours and is never
  // sampled (samples floor to at most dims + 2).
  cells_.assign(count, 0);
  corners_.assign(count, 0);
  for (int z = 0; z + 1 < pd.z; ++z)
    for (int y = 0; y + 1 < pd.y; ++y)
      for (int x = 0; x + 1 < pd.x; ++x) {
        const size_t i = z * pxy + y * px + x;
        const uint8_t* p = &padded_[i];
        const uint8_t v = p[0];
        if (p[1] == v && p[px] == v && p[px + 1] == v && p[pxy] == v && p[pxy + 1] == v &&
            p[pxy + px] == v && p[pxy + px + 1] == v) {
          cells_[i] = static_cast<uint16_t>(0x100 | v);
        }
        uint64_t c = 0;
        // y varies fastest, then x, then z (see corners()).
        const size_t offsets[8] = {0, px, 1, px + 1, pxy, pxy + px, pxy + 1, pxy + px + 1};
        for (int k = 0; k < 8; ++k)
          c |= static_cast<uint64_t>(p[offsets[k]]) << (8 * k);
        corners_[i] = c;
      }
}

RotationFrame::RotationFrame(const PreparedTool& tool, const glm::mat3& rotation,
                             glm::vec3 position, Sampling sampling)
    : sampling_(sampling) {
  const glm::dvec3 pivot(tool.pivot());
  const glm::dvec3 pos(position);
  const glm::dmat3 r(rotation);
  const glm::dvec3 d(tool.dims());
  // The support of the samples in tool coordinates: trilinear reaches one
  // voxel beyond the outer centres, nearest half a voxel.
  const double margin = sampling == Sampling::kNearest ? 0.5 : 1.0;
  glm::dvec3 lo(1e300), hi(-1e300);
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 corner((c & 1) ? d.x - 1 + margin : -margin,
                            (c & 2) ? d.y - 1 + margin : -margin,
                            (c & 4) ? d.z - 1 + margin : -margin);
    const glm::dvec3 k = r * (corner - pivot) + pos;
    lo = glm::min(lo, k);
    hi = glm::max(hi, k);
  }
  // Target voxels strictly inside the support (trilinear: samples on its
  // border weigh 0) or on its low border (nearest: t = -0.5 rounds to voxel
  // 0). The 1e-9 absorbs rounding of exact quarter turns, so their box is
  // exactly the tool's.
  constexpr double kEps = 1e-9;
  const glm::dvec3 box_lo =
      sampling == Sampling::kNearest ? glm::ceil(lo - kEps) : glm::floor(lo + kEps) + 1.0;
  box_ = Box{glm::ivec3(box_lo), glm::ivec3(glm::ceil(hi - kEps))};

  const glm::dmat3 inv = glm::transpose(r);
  const glm::dvec3 s0 = inv * (glm::dvec3(box_.lo) - pos) + pivot + sample_shift(sampling);
  for (int i = 0; i < 3; ++i) {
    origin_[i] = to_fixed(s0[i]);
    // Voxels 0 .. d-1 sit at padded kPad .. d-1+kPad; a cell reaching any of
    // them starts at kPad - 1 .. d - 1 + kPad.
    support_hi_[i] = tool.dims()[i] + kPad;
  }
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 3; ++i)
      step_[a][i] = to_fixed(inv[a][i]);  // component i of inv * e_a
  for (int i = 0; i < 3; ++i)
    inv_step_x_[i] = step_[0][i] != 0 ? 1.0 / step_[0][i] : 0.0;
  for (int i = 0; i < 3; ++i)
    centre_[i] = static_cast<float>(pos[i] - box_.lo[i]);

  // The balls are tested at exact target positions, the samples taken at
  // fixed-point ones: each of the box's steps is off by at most 2^-17 per
  // component (and a float rotation is orthonormal to about 1e-7), so a
  // sample is within (1 + steps) * 2^-17 * sqrt 3 + 1e-6 * distance of where
  // the balls assume. `error` is more than 7 times that bound.
  const glm::ivec3 size = box_.size();
  const double error = 0.01 + 1e-4 * (size.x + size.y + size.z);
  // spans() works in float, eight rows per instruction, so the balls absorb
  // its rounding too: the squared distances and chords are off by a few
  // 2^-24 of the squared radius (hence the relative widening of the
  // squares, which also covers the centre's rounding), the chord ends by a
  // few 2^-24 of the box size (float_error).
  const double float_error = 1e-3 + 1e-5 * (size.x + size.y + size.z);
  constexpr double kSquareError = 4e-6;
  const double reach = tool.reach_vox(sampling) + error + float_error;
  reach2_ = static_cast<float>(reach * reach * (1.0 + kSquareError) + 1e-3);
  const double core = static_cast<double>(tool.core_radius_vox(sampling)) - error - float_error;
  const double core2 = core * core * (1.0 - kSquareError) - 1e-3;
  core2_ = core > 0.0 && core2 > 0.0 ? static_cast<float>(core2) : -1.0f;
  core_value_ = tool.core_value();
  // Samples whose cell floor(s) lies in [0, dims + kPad] per axis read inside
  // the padded grid (both kernels, both samplings): tool coordinates in
  // [-kPad, dims + 1).
  clip_support_ = false;
  for (int i = 0; i < 3; ++i)
    if (pivot[i] - reach < -kPad || pivot[i] + reach >= d[i] + 1.0) clip_support_ = true;
}

uint8_t RotationFrame::sample_voxel(const PreparedTool& tool, glm::ivec3 k) const {
  const glm::ivec3 n = k - box_.lo;
  int32_t s[3];
  for (int i = 0; i < 3; ++i)
    s[i] = origin_[i] + n.x * step_[0][i] + n.y * step_[1][i] + n.z * step_[2][i];
  for (int i = 0; i < 3; ++i) {
    const int32_t c = s[i] >> kFracBits;
    if (c < kPad - 1 || c >= support_hi_[i]) return 0;
  }
  const glm::ivec3 pd = tool.padded_dims();
  const size_t i = cell_index(s, pd);
  if (sampling_ == Sampling::kNearest) return tool.padded()[i];
  return trilinear_at(tool.padded(), i, s, pd.x, static_cast<size_t>(pd.x) * pd.y);
}

bool RotationFrame::clip_line(Line& line) const {
  // The stretch of the line s0 + n * step within the support, widened by
  // half a voxel so rounding of the (double) bounds can only add samples that
  // read zero padding; the padding keeps every sample inside the grid.
  double lo = 0.0, hi = line.n;
  for (int i = 0; i < 3; ++i) {
    const double a = ((kPad - 1 - 0.5) * kOne - line.s[i]);
    const double b = ((support_hi_[i] + 0.5) * kOne - line.s[i]);
    if (step_[0][i] == 0) {
      if (a > 0.0 || b <= 0.0) return false;
      continue;
    }
    double e0 = a * inv_step_x_[i], e1 = b * inv_step_x_[i];
    if (e0 > e1) std::swap(e0, e1);
    lo = std::max(lo, fast_ceil(e0));
    hi = std::min(hi, fast_floor(e1) + 1.0);
  }
  if (lo >= hi) return false;
  const int n0 = static_cast<int>(lo), n1 = static_cast<int>(hi);
  for (int i = 0; i < 3; ++i)
    line.s[i] += n0 * step_[0][i];
  line.out += n0;
  line.n = n1 - n0;
  return true;
}

void RotationFrame::sample_lines(const PreparedTool& tool, const Lines& lines,
                                 const uint8_t* end) const {
  const glm::ivec3 pd = tool.padded_dims();
  const bool nearest = sampling_ == Sampling::kNearest;
#ifdef SCULPT_TOOL_AVX2
  if (g_vector_kernel.load(std::memory_order_relaxed) && cpu_has_avx2()) {
    sample_lines_avx2(tool.padded(), tool.corners(), pd, step_[0], lines, end, nearest);
    return;
  }
#endif
  const size_t px = pd.x, pxy = px * pd.y;
  const uint8_t* padded = tool.padded();
  const uint16_t* cells = tool.cells();
  const int32_t st[3] = {step_[0][0], step_[0][1], step_[0][2]};
  for (int l = 0; l < lines.count; ++l) {
    int32_t s[3] = {lines.s0[l], lines.s1[l], lines.s2[l]};
    uint8_t* out = lines.out[l];
    const int n1 = lines.n[l];
    if (nearest) {
      for (int n = 0; n < n1; ++n) {
        out[n] = padded[cell_index(s, pd)];
        s[0] += st[0];
        s[1] += st[1];
        s[2] += st[2];
      }
      continue;
    }
    for (int n = 0; n < n1; ++n) {
      const size_t i = cell_index(s, pd);
      const uint16_t c = cells[i];
      out[n] = c != 0 ? static_cast<uint8_t>(c) : trilinear_at(padded, i, s, px, pxy);
      s[0] += st[0];
      s[1] += st[1];
      s[2] += st[2];
    }
  }
}

bool RotationFrame::reach_span(int y, int z, int& x0, int& x1) const {
  Spans sp;
  const SpanRun run{y, z, 1, 0};
  spans(&run, 1, sp);
  x0 = std::max(x0, sp.x0[0]);
  x1 = std::min(x1, sp.x1[0]);
  return x0 < x1;
}

namespace {

// One row's span from its squared distance to the balls' axis, in the same
// float operations as the eight-row version below, so both give the same
// spans: ceil and floor by truncation, as the baseline x86-64 has no
// rounding instruction.
inline float trunc_ceil(float v) {
  const auto t = static_cast<float>(static_cast<int32_t>(v));
  return t < v ? t + 1.0f : t;
}
inline float trunc_floor(float v) {
  const auto t = static_cast<float>(static_cast<int32_t>(v));
  return t > v ? t - 1.0f : t;
}

}  // namespace

#ifdef SCULPT_TOOL_AVX2
namespace {

// The float operations of spans()' scalar loop, eight rows at a time: the
// same IEEE operations per lane, so the same spans. Per row, two square
// roots and four roundings; one row at a time their latency cost a third
// of a 16^3 tool's rotation, four at a time (SSE) still 14%.
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
__attribute__((target("avx2"))) void spans_avx2(const RotationFrame::SpanRun* runs, int count,
                                                float cx, float cy, float cz, float reach2,
                                                float core2, float width, int32_t* x0s,
                                                int32_t* x1s, int32_t* c0s, int32_t* c1s) {
  const __m256 vcx = _mm256_set1_ps(cx), vcy = _mm256_set1_ps(cy);
  const __m256 vreach2 = _mm256_set1_ps(reach2), vcore2 = _mm256_set1_ps(core2);
  const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f);
  const __m256 vwidth = _mm256_set1_ps(width);
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const bool any_core = core2 > 0.0f;
  for (int r = 0; r < count; ++r) {
    const RotationFrame::SpanRun& run = runs[r];
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
      store8(x0s + at, x0);
      store8(x1s + at, x1);
      store8(c0s + at, c0);
      store8(c1s + at, c1);
    }
  }
}

}  // namespace
#endif

void RotationFrame::spans(const SpanRun* runs, int count, Spans& out) const {
  assert(count == 0 || runs[count - 1].at + runs[count - 1].n <= kSpanRows);
  const float width = static_cast<float>(box_.size().x);
  const float cx = centre_[0];
#ifdef SCULPT_TOOL_AVX2
  static_assert(kSpanRows % 8 == 0);
  // A single row (the cache asks row by row) costs less one lane wide.
  const bool one_row = count == 1 && runs[0].n == 1;
  if (!one_row && g_vector_kernel.load(std::memory_order_relaxed) && cpu_has_avx2()) {
    spans_avx2(runs, count, cx, centre_[1], centre_[2], reach2_, core2_, width, out.x0, out.x1,
               out.c0, out.c1);
    return;
  }
#endif
  for (int r = 0; r < count; ++r) {
    const SpanRun& run = runs[r];
    const float dz = static_cast<float>(run.z) - centre_[2];
    const float dz2 = dz * dz;
    for (int i = 0; i < run.n; ++i) {
      const int at = run.at + i;
      const float dy = static_cast<float>(run.y0 + i) - centre_[1];
      const float r2 = dy * dy + dz2;
      const float h2 = reach2_ - r2;
      const float h = std::sqrt(std::max(h2, 0.0f));
      float x0 = std::max(0.0f, trunc_ceil(cx - h));
      float x1 = std::min(width, trunc_floor(cx + h) + 1.0f);
      if (!(h2 >= 0.0f && x0 < x1)) x0 = x1 = 0.0f;
      const float k2 = core2_ - r2;
      const float k = std::sqrt(std::max(k2, 0.0f));
      float c0 = x1, c1 = x1;
      if (core2_ > 0.0f && k2 > 0.0f) {
        c0 = std::min(std::max(trunc_ceil(cx - k), x0), x1);
        c1 = std::min(std::max(trunc_floor(cx + k) + 1.0f, c0), x1);
      }
      out.x0[at] = static_cast<int32_t>(x0);
      out.x1[at] = static_cast<int32_t>(x1);
      out.c0[at] = static_cast<int32_t>(c0);
      out.c1[at] = static_cast<int32_t>(c1);
    }
  }
}

void RotationFrame::reach_spans(int z, int16_t* x0, int16_t* x1) const {
  const glm::ivec3 size = box_.size();
  Spans sp;
  for (int ya = 0; ya < size.y; ya += kSpanRows) {
    const int n = std::min(kSpanRows, size.y - ya);
    const SpanRun run{ya, z, n, 0};
    spans(&run, 1, sp);
    for (int i = 0; i < n; ++i) {
      x0[ya + i] = static_cast<int16_t>(sp.x0[i]);
      x1[ya + i] = static_cast<int16_t>(sp.x1[i]);
    }
  }
}

void RotationFrame::plan_row(const int32_t row_s[3], int x0, int x1, Span span, uint8_t* out,
                             Lines& lines) const {
  const int first = x0;
  // The stretch within reach, and the core stretch [c0, c1) in it, which
  // needs no sampling.
  x0 = std::max(x0, span.x0);
  x1 = std::min(x1, span.x1);
  if (x0 >= x1) return;
  const int c0 = std::clamp(span.c0, x0, x1);
  const int c1 = std::clamp(span.c1, c0, x1);
  auto add_line = [&](int a, int b) {
    Line line;
    for (int i = 0; i < 3; ++i)
      line.s[i] = row_s[i] + a * step_[0][i];
    line.n = b - a;
    line.out = out + (a - first);
    if (!clip_support_ || clip_line(line)) lines.add(line);
  };
  // A short core is sampled with the rest (its samples are the core value
  // anyway): one line instead of two costs less than the few samples.
  if (c1 - c0 < kMinCoreRun) {
    add_line(x0, x1);
    return;
  }
  if (core_value_ != 0) std::memset(out + (c0 - first), core_value_, c1 - c0);
  if (x0 < c0) add_line(x0, c0);
  if (c1 < x1) add_line(c1, x1);
}

#ifdef SCULPT_TOOL_AVX2
namespace {

__attribute__((target("avx2"), always_inline)) inline __m256i load(const int32_t* p) {
  return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
}
__attribute__((target("avx2"), always_inline)) inline void store(int32_t* p, __m256i v) {
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), v);
}

// Lines k .. k + 7 of `lines`, one per row of eight: row r's starts at x
// offset start[r] with n[r] samples, its first sample at row_s + r J +
// start I and its output at out + r width + start.
__attribute__((target("avx2"), always_inline)) inline void put_lines(
    RotationFrame::Lines& lines, int k, const int32_t row_s[3], const int32_t step_i[3],
    const int32_t step_j[3], __m256i start, __m256i n, int width, uint8_t* out) {
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
// become lines of no samples rather than branches. Row by row, this
// planning cost a third of a 16^3 tool's rotation.
__attribute__((target("avx2"))) void plan_rows_avx2(const int32_t row_s[3], const int32_t step_i[3],
                                                    const int32_t step_j[3], const int32_t* x0s,
                                                    const int32_t* x1s, const int32_t* c0s,
                                                    const int32_t* c1s, int m, int width,
                                                    uint8_t core_value, uint8_t* out,
                                                    RotationFrame::Lines& lines) {
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i x0 = load(x0s), x1 = load(x1s);
  const __m256i c0 = _mm256_min_epi32(_mm256_max_epi32(load(c0s), x0), x1);
  const __m256i c1 = _mm256_min_epi32(_mm256_max_epi32(load(c1s), c0), x1);
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
#endif

void RotationFrame::plan_rows(const int32_t row_s[3], const Spans& sp, int i, int m, uint8_t* out,
                              Lines& lines) const {
  assert(m <= 8 && i + 8 <= kSpanRows && lines.count + 16 <= Lines::kCapacity);
  const int width = box_.size().x;
#ifdef SCULPT_TOOL_AVX2
  if (!clip_support_ && g_vector_kernel.load(std::memory_order_relaxed) && cpu_has_avx2()) {
    plan_rows_avx2(row_s, step_[0], step_[1], sp.x0 + i, sp.x1 + i, sp.c0 + i, sp.c1 + i, m, width,
                   core_value_, out, lines);
    return;
  }
#endif
  int32_t s[3] = {row_s[0], row_s[1], row_s[2]};
  for (int r = 0; r < m; ++r, out += width) {
    plan_row(s, 0, width, sp.row(i + r), out, lines);
    for (int a = 0; a < 3; ++a)
      s[a] += step_[1][a];
  }
}

void RotationFrame::sample_row(const PreparedTool& tool, int y, int z, int x0, int x1,
                               uint8_t* out) const {
  assert(x0 <= x1);
  const int ry = y - box_.lo.y, rz = z - box_.lo.z;
  Spans sp;
  const SpanRun run{ry, rz, 1, 0};
  spans(&run, 1, sp);
  int32_t row_s[3];
  for (int i = 0; i < 3; ++i)
    row_s[i] = origin_[i] + ry * step_[1][i] + rz * step_[2][i];
  Lines lines;
  plan_row(row_s, x0 - box_.lo.x, x1 - box_.lo.x, sp.row(0), out, lines);
  sample_lines(tool, lines, out + (x1 - x0));
}

void RotationFrame::sample_box(const PreparedTool& tool, uint8_t* out) const {
  const glm::ivec3 size = box_.size();
  const uint8_t* end = out + static_cast<size_t>(size.x) * size.y * size.z;
  // The rows of several planes are given their spans together, then
  // planned eight at a time into a batch of lines, which is sampled when
  // full: each stage's set-up is paid per batch rather than per row.
  Spans sp;
  constexpr int kRuns = kSpanRows / 8;
  SpanRun runs[kRuns];
  int count = 0, used = 0;
  Lines lines;
  auto plan = [&] {
    if (count == 0) return;
    spans(runs, count, sp);
    for (int r = 0; r < count; ++r) {
      const SpanRun& run = runs[r];
      uint8_t* dst = out + (static_cast<size_t>(run.z) * size.y + run.y0) * size.x;
      // Algorithm 1: each row's first sample one J step from the previous.
      int32_t row_s[3];
      for (int i = 0; i < 3; ++i)
        row_s[i] = origin_[i] + run.y0 * step_[1][i] + run.z * step_[2][i];
      for (int i = 0; i < run.n; i += 8) {
        if (lines.count + 16 > Lines::kCapacity) {
          sample_lines(tool, lines, end);
          lines.count = 0;
        }
        const int m = std::min(8, run.n - i);
        plan_rows(row_s, sp, run.at + i, m, dst, lines);
        dst += static_cast<size_t>(m) * size.x;
        for (int a = 0; a < 3; ++a)
          row_s[a] += m * step_[1][a];
      }
    }
    count = used = 0;
  };
  for (int z = 0; z < size.z; ++z) {
    // Only the rows of this plane that cross the reach ball.
    const double dz = z - static_cast<double>(centre_[2]);
    const double h2 = static_cast<double>(reach2_) - dz * dz;
    if (h2 < 0.0) continue;
    const double h = std::sqrt(h2);
    const int y0 = std::max(0, static_cast<int>(fast_ceil(centre_[1] - h)));
    const int y1 = std::min(size.y, static_cast<int>(fast_floor(centre_[1] + h)) + 1);
    for (int ya = y0; ya < y1; ya += kSpanRows) {
      const int n = std::min(kSpanRows, y1 - ya);
      const int slots = (n + 7) & ~7;
      if (used + slots > kSpanRows) plan();
      runs[count++] = SpanRun{ya, z, n, used};
      used += slots;
    }
  }
  plan();
  sample_lines(tool, lines, end);
}

RotatedTool rotate_tool(const PreparedTool& tool, const glm::mat3& rotation, glm::vec3 position,
                        RotationMethod method, Sampling sampling) {
  const RotationFrame frame(tool, rotation, position, sampling);
  const Box& box = frame.box();
  RotatedTool out{DenseGrid<uint8_t>(box.size()), box.lo};
  uint8_t* dst = out.density.data();
  if (method == RotationMethod::kBrute) {
    // Every target voxel: a full matrix product and a bounds test.
    for (int z = box.lo.z; z < box.hi.z; ++z)
      for (int y = box.lo.y; y < box.hi.y; ++y)
        for (int x = box.lo.x; x < box.hi.x; ++x)
          *dst++ = frame.sample_voxel(tool, {x, y, z});
    return out;
  }
  frame.sample_box(tool, dst);
  return out;
}

RotatedTool rotate_tool_about_pivot(const PreparedTool& tool, const glm::mat3& rotation,
                                    RotationMethod method, Sampling sampling) {
  return rotate_tool(tool, rotation, tool.pivot(), method, sampling);
}

RotatedTool rotate_tool_direct(const PreparedTool& tool, const glm::mat3& rotation,
                               glm::vec3 position) {
  const RotationFrame frame(tool, rotation, position, Sampling::kNearest);
  const Box& box = frame.box();
  RotatedTool out{DenseGrid<uint8_t>(box.size()), box.lo};
  const DenseGrid<uint8_t>& src = tool.tool().density;
  const glm::ivec3 d = src.dims();
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        const glm::vec3 w = rotation * (glm::vec3(x, y, z) - tool.pivot()) + position;
        const glm::ivec3 k(glm::floor(w + 0.5f));
        if (!box.contains(k)) continue;
        const glm::ivec3 n = k - box.lo;
        out.density.at(n.x, n.y, n.z) = src.at(x, y, z);
      }
  return out;
}

}  // namespace sculpt::core
