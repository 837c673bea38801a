#pragma once
// Shapes and measures the ball brushes' tests share: a slab whose top is a
// height field, the height of its top per column, a ball's radius per
// direction, the material's mass.

#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/core/sculpt/stroke.h"
#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core::test {

constexpr int kSlabN = 64;
constexpr float kSlabTop = 32.0f;

/// A kSlabN^3 volume filled below z = height(x, y) (the density of the
/// vertical distance to it).
inline Volume slab(const std::function<float(float x, float y)>& height) {
  DenseGrid<uint8_t> g{glm::ivec3(kSlabN)};
  for (int z = 0; z < kSlabN; ++z)
    for (int y = 0; y < kSlabN; ++y)
      for (int x = 0; x < kSlabN; ++x)
        g.at(x, y, z) = density_from_distance(static_cast<float>(z) -
                                              height(static_cast<float>(x), static_cast<float>(y)));
  return Volume::from_dense(g);
}

/// The slab with bumps of +-amplitude, 8 voxels apart, on its top at kSlabTop.
inline Volume bumpy_slab(float amplitude) {
  return slab([amplitude](float x, float y) {
    return kSlabTop + amplitude * std::sin(x * 0.785398f) * std::cos(y * 0.785398f);
  });
}

/// The height of the top of column (x, y): where the density, read downward
/// from the top, first reaches 127.5 (linear between voxels).
inline float top_height(const DenseGrid<uint8_t>& g, int x, int y) {
  for (int z = g.dims().z - 2; z >= 0; --z) {
    const float lo = g.at(x, y, z), hi = g.at(x, y, z + 1);
    if (lo >= 127.5f && hi < 127.5f) return static_cast<float>(z) + (lo - 127.5f) / (lo - hi);
  }
  return -1.0f;
}

/// Mean and variance of the top's height over columns x in [x0, x1), y in [y0, y1).
struct HeightStats {
  double mean = 0.0, variance = 0.0;
};
inline HeightStats top_stats(const Volume& v, int x0, int x1, int y0, int y1) {
  const DenseGrid<uint8_t> g = v.to_dense();
  double s = 0.0, s2 = 0.0;
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const double h = top_height(g, x, y);
      s += h;
      s2 += h * h;
      ++n;
    }
  const double mean = s / n;
  return {mean, s2 / n - mean * mean};
}

/// The material's volume in voxels (density sum / 255).
inline double mass(const Volume& v) {
  const DenseGrid<uint8_t> g = v.to_dense();
  double m = 0.0;
  for (uint8_t x : g.values())
    m += x;
  return m / 255.0;
}

/// A straight path from a to b, samples a voxel apart.
inline std::vector<StrokeSample> line_path(glm::vec3 a, glm::vec3 b) {
  const int n = std::max(1, static_cast<int>(std::ceil(glm::length(b - a))));
  std::vector<StrokeSample> path;
  for (int i = 0; i <= n; ++i)
    path.push_back({a + (b - a) * (static_cast<float>(i) / static_cast<float>(n)), {}});
  return path;
}

}  // namespace sculpt::core::test
