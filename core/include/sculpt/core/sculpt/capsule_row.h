#pragma once
// A ball swept along a segment (a capsule), across one row of voxels: which
// stretch of the row it reaches, and what a swept stroke (stroke.h) fills
// there. The row kernels of the ball's stroke and of the ball brushes' path.

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/vec3.hpp>

#include "sculpt/core/tool/tool.h"

namespace sculpt::core {

/// The row's constants: the row (y, z) and the segment a -> a + ab, in
/// material voxels.
struct CapsuleRow {
  float a_x = 0.0f;              // the segment's start, x
  glm::vec3 ab{0.0f};            // the segment
  float inv_ab2 = 0.0f;          // 1 / |ab|^2, 0 for a point
  float apy = 0.0f, apz = 0.0f;  // the row's y and z from the segment's start
  float dot_yz = 0.0f;           // (apy, apz) . (ab.y, ab.z)
  float radius = 0.0f;
  float inner2 = -1.0f;  // radius - 1, squared (-1: no inside)
  float reach2 = 0.0f;   // radius + 1, squared
};

/// A hard ball's filling of voxel x of the row: 255 within radius - 1, 0
/// from the reach on, in between tool_density()'s bytes for hardness 1,
/// without a branch. std::min and std::max rather than std::clamp (the same
/// values: nothing here is NaN), whose references GCC leaves as branches;
/// with -fno-trapping-math (core/CMakeLists.txt) a loop of these runs a
/// vector at a time.
inline uint8_t hard_capsule_filling(const CapsuleRow& c, int x) {
  const float apx = static_cast<float>(x) - c.a_x;
  const float t = std::min(std::max((apx * c.ab.x + c.dot_yz) * c.inv_ab2, 0.0f), 1.0f);
  const float dx = apx - t * c.ab.x, dy = c.apy - t * c.ab.y, dz = c.apz - t * c.ab.z;
  const float d2 = dx * dx + dy * dy + dz * dz;
  const float d = std::sqrt(d2) - c.radius;
  float f = std::min(std::max(127.5f - d * 127.5f, 0.0f), 255.0f);
  f = d2 > c.inner2 ? f : 255.0f;
  f = d2 < c.reach2 ? f : 0.0f;
  return static_cast<uint8_t>(f);
}

/// Raises out[i] to the hard ball's filling of voxel x0 + i, i in [0, n).
inline void raise_hard_capsule_row(const CapsuleRow& row, int x0, int n, uint8_t* __restrict out) {
  const CapsuleRow c = row;  // a copy: stores to `out` cannot alias it
  for (int i = 0; i < n; ++i)
    out[i] = std::max(out[i], hard_capsule_filling(c, x0 + i));
}

/// A ball of any hardness at one voxel of the row (x from the segment's
/// start apx): tool_density() of its distance to the segment, 0 from the
/// reach on.
inline uint8_t capsule_filling(const CapsuleRow& c, float apx, float hardness) {
  const float t = std::clamp((apx * c.ab.x + c.dot_yz) * c.inv_ab2, 0.0f, 1.0f);
  const float dx = apx - t * c.ab.x, dy = c.apy - t * c.ab.y, dz = c.apz - t * c.ab.z;
  const float d2 = dx * dx + dy * dy + dz * dz;
  if (d2 >= c.reach2) return 0;
  return tool_density(std::sqrt(d2) - c.radius, c.radius, hardness);
}

// std::floor() and std::ceil() to int, for |x| < 2^31: without SSE4.1 (the
// build targets plain x86-64) those are library calls, four a row of spans.
inline int floor_int(float x) {
  const int i = static_cast<int>(x);
  return i - (static_cast<float>(i) > x);
}
inline int ceil_int(float x) {
  const int i = static_cast<int>(x);
  return i + (static_cast<float>(i) < x);
}

/// The stretch [lo, hi] of the row line (x, y, z), x real, within sqrt(rho2)
/// of the segment a -> a + ab (ab2 = |ab|^2; 0: the ball around a alone),
/// for rows y0 .. y0 + n - 1 of the plane z, row i missing where lo[i] >
/// hi[i]. `outer`: where the cylinder's quadratic is too flat to solve in
/// float (the segment nearly along x) the whole line is taken, so an outer
/// stretch never misses a point; else none is (the ends alone), so an inner
/// one never takes too many. Widen it by a voxel against rounding before
/// measuring voxels one by one.
void capsule_rows(glm::vec3 a, glm::vec3 ab, float ab2, int y0, int n, float z, float rho2,
                  bool outer, float* __restrict lo, float* __restrict hi);

/// Where a row's coverage grew: [begin, end), empty when begin >= end.
struct GrownStretch {
  int begin = 0, end = 0;
};

/// Raises cov[lo, hi) to fill[lo, hi) and returns where it grew.
GrownStretch raise_coverage(const uint8_t* fill, uint8_t* cov, int lo, int hi);

/// Raises cov[lo, hi) to the hard ball's filling of voxels x0 + [lo, hi)
/// (the row's voxel x0 is cov[0]) and returns where it grew; `fill` is
/// scratch of at least hi bytes. cov must stay readable and writable for 32
/// bytes from cov[0] when hi <= 32 (a brick row with its slack): there, with
/// AVX2, the row is one 32-byte step whose bytes outside [lo, hi) are stored
/// back unchanged (not safe if another thread writes them meanwhile).
/// [in_lo, in_hi) (empty by default) may name voxels the caller knows lie
/// within radius - 1 with a voxel to spare: their filling is 255 and is not
/// measured (a big ball's rows are mostly inside). The result is
/// grow_hard_capsule_row_scalar()'s either way.
GrownStretch grow_hard_capsule_row(const CapsuleRow& c, int x0, int lo, int hi, uint8_t* cov,
                                   uint8_t* fill, int in_lo = 0, int in_hi = 0);

/// The same, a voxel at a time, every voxel measured (the reference).
GrownStretch grow_hard_capsule_row_scalar(const CapsuleRow& c, int x0, int lo, int hi, uint8_t* cov,
                                          uint8_t* fill);

}  // namespace sculpt::core
