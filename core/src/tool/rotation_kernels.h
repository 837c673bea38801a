#pragma once
// The inner loops of RotationFrame (tool_rotation.h), private to sculpt_core:
// the batch layouts they exchange, and one table of kernels per instruction
// set (rotation_kernels_scalar.cpp, rotation_kernels_avx2.cpp). kernels() is
// the one place that chooses between them; both compute the same values in
// the same integer and float operations, so the choice never shows in a
// result.
//
// A frame works in three stages, each batched so that its set-up is paid
// per batch rather than per row: spans() finds each row's stretch within the
// tool's reach and its core, plan_rows() turns rows into lines of samples
// (filling the core), sample_lines() samples the lines.

#include <cstddef>
#include <cstdint>

#include "sculpt/core/tool/tool_rotation.h"

#if defined(__x86_64__) && defined(__GNUC__)
// AVX2 kernels built with per-function target attributes and chosen at run
// time, so the library still runs on any x86-64.
#define SCULPT_ROTATION_AVX2 1
#endif

namespace sculpt::core::rotation {

/// Fraction bits of the fixed-point map (16.16).
constexpr int kFracBits = 16;
/// Core stretches shorter than this are sampled rather than filled: one line
/// instead of two costs less than the few samples.
constexpr int kMinCoreRun = 16;

/// A stretch of samples along x: the first one's position (16.16, padded
/// tool voxels), the count, and where the values go.
struct Line {
  int32_t s[3];
  int n;
  uint8_t* out;
};

/// A batch of lines, one array per field (the planner writes eight rows'
/// lines with vector stores): the sampling kernels' input.
struct Lines {
  static constexpr int kCapacity = 256;
  int32_t s0[kCapacity], s1[kCapacity], s2[kCapacity], n[kCapacity];
  uint8_t* out[kCapacity];
  int count = 0;

  Line at(int i) const { return {{s0[i], s1[i], s2[i]}, n[i], out[i]}; }
  void put(int i, const Line& line) {
    s0[i] = line.s[0];
    s1[i] = line.s[1];
    s2[i] = line.s[2];
    n[i] = line.n;
    out[i] = line.out;
  }
  void add(const Line& line) { put(count++, line); }
};

/// A plane's rows y0 .. y0 + n - 1 (box-relative), whose spans go to index
/// `at` on (a multiple of 8) of a Spans.
struct SpanRun {
  int y0, z, n, at;
};

/// A box-relative row's stretch within the reach ball, [x0, x1) inside
/// [0, box width) (empty: x0 = x1 = 0), and within it the core stretch
/// [c0, c1) (empty: c0 = c1 = x1).
struct Span {
  int32_t x0, x1, c0, c1;
};

/// Spans of up to kSpanRows rows, one array per field (the vector kernels
/// load and store them eight at a time). Each run takes its rows rounded up
/// to a multiple of 8 from `at`, within kSpanRows.
constexpr int kSpanRows = 512;
static_assert(kSpanRows % 8 == 0);
struct Spans {
  int32_t x0[kSpanRows], x1[kSpanRows], c0[kSpanRows], c1[kSpanRows];
  Span row(int i) const { return {x0[i], x1[i], c0[i], c1[i]}; }
};

/// One instruction set's kernels. Every stride, step and offset is a
/// frame's: I = step_i and J = step_j are the inverse-rotated target x and y
/// steps (16.16, padded tool voxels), `width` the box's row length.
struct Kernels {
  /// Samples the lines (stepping by step_i) into their outputs, none of which
  /// reaches `end`; the kernel may rewrite (unchanged) bytes past a line's
  /// end before `end`.
  void (*sample_lines)(const PreparedTool& tool, Sampling sampling, const int32_t step_i[3],
                       const Lines& lines, const uint8_t* end);
  /// The spans of the runs' rows, for the reach ball of squared radius
  /// reach2 and the core ball of squared radius core2 (<= 0: none) round
  /// `centre` (box-relative voxels), in rows `width` long.
  void (*spans)(const float centre[3], float reach2, float core2, float width, const SpanRun* runs,
                int count, Spans& out);
  /// Rows i .. i + m - 1 (m <= 8) of `sp`, whole (x offsets [0, width)), the
  /// first starting at row_s and writing from out, a row `width` apart:
  /// plan_row() for each (a vector kernel may add lines of no samples).
  void (*plan_rows)(const int32_t row_s[3], const int32_t step_i[3], const int32_t step_j[3],
                    int width, uint8_t core_value, const Spans& sp, int i, int m, uint8_t* out,
                    Lines& lines);
};

extern const Kernels kScalarKernels;
#ifdef SCULPT_ROTATION_AVX2
extern const Kernels kAvx2Kernels;
#endif

/// The kernels to use: AVX2 when use_vector_kernel() allows it and the CPU
/// has it, else scalar. The only test of either (tool_rotation.cpp).
const Kernels& kernels();

/// Box-relative row whose first sample (x = 0) is at row_s, x offsets
/// [x0, x1) written from out[0]: fills the core stretch of `span` with
/// core_value and adds the stretches left to sample (at most 2) to lines,
/// not clipped to the tool's support.
void plan_row(const int32_t row_s[3], const int32_t step_i[3], int x0, int x1, Span span,
              uint8_t core_value, uint8_t* out, Lines& lines);

/// Index in the padded grid of the cell (voxel) that sample s floors to.
inline size_t cell_index(const int32_t s[3], glm::ivec3 pd) {
  return (static_cast<size_t>(s[2] >> kFracBits) * pd.y + static_cast<size_t>(s[1] >> kFracBits)) *
             pd.x +
         static_cast<size_t>(s[0] >> kFracBits);
}

/// Trilinear sample of cell i with 8-bit weights: each axis' pair sums to
/// 256, so an equal-cornered cell returns its value exactly and the 32-bit
/// sum cannot overflow (255 * 2^24 + 2^23 < 2^32).
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

}  // namespace sculpt::core::rotation
