#pragma once
// Internal to the mesh module: the one interpolation between levels that
// every sample of mixed levels is made with (mixed_level_mesh.cpp,
// interim_mesh.cpp), so that a sample interpolated anywhere is the same
// float to the bit.

#include <glm/vec3.hpp>

namespace sculpt::core::detail {

/// Corner k of a unit cube (bit 0 x, bit 1 y, bit 2 z).
constexpr glm::ivec3 cube_corner(int k) {
  return {k & 1, (k >> 1) & 1, k >> 2};
}

// The interpolant at level-0 point x of the values at the level-`lambda`
// grid's points around it (value_at(i), i a level-lambda point): bilinear on
// a face of that grid, linear on an edge, the point's own value on a point.
// One function for every caller, so a sample interpolated anywhere is the
// same float to the bit.
template <class ValueAt>
float interpolate(glm::ivec3 x, int lambda, const ValueAt& value_at) {
  const int big = 1 << lambda;
  glm::ivec3 i0;
  glm::vec3 w;
  for (int a = 0; a < 3; ++a) {
    i0[a] = x[a] / big;
    w[a] = static_cast<float>(x[a] - i0[a] * big) / static_cast<float>(big);
  }
  float value = 0.0f;
  for (int c = 0; c < 8; ++c) {
    const glm::ivec3 o = cube_corner(c);
    float weight = 1.0f;
    for (int a = 0; a < 3; ++a)
      weight *= o[a] ? w[a] : 1.0f - w[a];
    if (weight == 0.0f) continue;
    value += weight * value_at(i0 + o);
  }
  return value;
}

}  // namespace sculpt::core::detail
