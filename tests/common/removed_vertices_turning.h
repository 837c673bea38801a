#pragma once
// Marched vertices a simplifier removed whose normal lies further than a
// limit from the normal the simplified mesh interpolates at their nearest
// point (core::NormalTurnLimit::max_removed_deg): where the clay turns one
// way and back between a made triangle's corners, what shows as a light
// blob on the drawn clay. Counted independently of the simplifier: a
// vertex is "removed" when no simplified vertex has its position, and its
// nearest triangle is sought among all of them, its barycentric weights
// taken from areas.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <tuple>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "sculpt/core/mesh/mesh.h"
#include "sculpt/core/mesh/point_triangle.h"

namespace sculpt::test {

inline int64_t removed_vertices_turning(const core::Mesh& marched, const core::Mesh& simplified,
                                        float max_deg) {
  auto key = [](glm::vec3 p) { return std::make_tuple(p.x, p.y, p.z); };
  std::set<std::tuple<float, float, float>> kept;
  for (const glm::vec3& p : simplified.positions)
    kept.insert(key(p));
  // A thousandth of a degree for float rounding near the bound.
  const double limit = static_cast<double>(max_deg) + 1e-3;
  int64_t turning = 0;
  for (size_t v = 0; v < marched.positions.size(); ++v) {
    const glm::vec3 p = marched.positions[v];
    if (kept.contains(key(p))) continue;
    float best = std::numeric_limits<float>::max();
    glm::vec3 nearest(0.0f);
    glm::uvec3 corners(0);
    for (const glm::uvec3& t : simplified.triangles) {
      const core::ClosestPoint c = core::closest_point_on_triangle(
          p, simplified.positions[t.x], simplified.positions[t.y], simplified.positions[t.z]);
      if (c.distance_squared < best) {
        best = c.distance_squared;
        nearest = c.point;
        corners = t;
      }
    }
    if (best == std::numeric_limits<float>::max()) continue;  // nothing left to be near
    const glm::vec3 a = simplified.positions[corners.x], b = simplified.positions[corners.y],
                    c = simplified.positions[corners.z];
    // Each corner's weight: the area of the triangle the point makes with
    // the other two, over the whole.
    const float whole = glm::length(glm::cross(b - a, c - a));
    glm::vec3 w(1.0f / 3.0f);
    if (whole > 0.0f)
      w = glm::vec3(glm::length(glm::cross(b - nearest, c - nearest)),
                    glm::length(glm::cross(c - nearest, a - nearest)),
                    glm::length(glm::cross(a - nearest, b - nearest))) /
          whole;
    const glm::vec3 n = w.x * simplified.normals[corners.x] + w.y * simplified.normals[corners.y] +
                        w.z * simplified.normals[corners.z];
    const double cos = glm::dot(glm::normalize(n), marched.normals[v]);
    turning += glm::degrees(std::acos(std::clamp(cos, -1.0, 1.0))) > limit;
  }
  return turning;
}

}  // namespace sculpt::test
