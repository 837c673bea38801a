#include "sculpt/core/distance/brute_distance.h"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "sculpt/core/mesh/point_triangle.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

template <class Dist2>
DenseGrid<float> brute(glm::ivec3 dims, size_t count, Dist2 dist2, int threads) {
  DenseGrid<float> out(dims);
  parallel_for(
      dims.z,
      [&](int64_t z) {
        for (int y = 0; y < dims.y; ++y)
          for (int x = 0; x < dims.x; ++x) {
            const glm::vec3 p{float(x), float(y), float(z)};
            float best = std::numeric_limits<float>::infinity();
            for (size_t i = 0; i < count; ++i)
              best = std::min(best, dist2(p, i));
            out.at(x, y, int(z)) = std::sqrt(best);
          }
      },
      threads);
  return out;
}

}  // namespace

DenseGrid<float> brute_distance_to_points(glm::ivec3 dims, const std::vector<glm::vec3>& points,
                                          int threads) {
  return brute(
      dims, points.size(),
      [&](glm::vec3 p, size_t i) {
        const glm::vec3 d = p - points[i];
        return glm::dot(d, d);
      },
      threads);
}

DenseGrid<float> brute_distance_to_triangles(glm::ivec3 dims,
                                             const std::vector<Triangle3>& triangles, int threads) {
  return brute(
      dims, triangles.size(),
      [&](glm::vec3 p, size_t i) {
        const Triangle3& t = triangles[i];
        return point_triangle_distance_squared(p, t.a, t.b, t.c);
      },
      threads);
}

std::vector<glm::vec3> voxel_positions(const DenseGrid<uint8_t>& mask, uint8_t value) {
  std::vector<glm::vec3> out;
  const glm::ivec3 d = mask.dims();
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x)
        if (mask.at(x, y, z) == value) out.emplace_back(float(x), float(y), float(z));
  return out;
}

}  // namespace sculpt::core
