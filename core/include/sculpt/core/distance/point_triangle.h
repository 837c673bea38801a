#pragma once
// Exact Euclidean distance from a point to a triangle (Jones & Satherley §3.2,
// the closest-point regions of Jones' CSR-5-95: the plane, an edge or a
// vertex). Coordinates in voxel units.

#include <cstdint>

#include <glm/vec3.hpp>

namespace sculpt::core {

/// Which part of a triangle is closest to a point.
enum class TriangleFeature : uint8_t {
  kFace,
  kVertexA,
  kVertexB,
  kVertexC,
  kEdgeAB,
  kEdgeBC,
  kEdgeCA
};

struct ClosestPoint {
  glm::vec3 point{0.0f};
  float distance_squared = 0.0f;
  TriangleFeature feature = TriangleFeature::kFace;
};

/// The point of triangle (a, b, c) closest to p and which feature it lies on.
/// Degenerate triangles (collinear or coincident corners) are handled.
ClosestPoint closest_point_on_triangle(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c);

/// Squared distance from p to triangle (a, b, c), voxel units squared.
inline float point_triangle_distance_squared(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  return closest_point_on_triangle(p, a, b, c).distance_squared;
}

/// Squared distance from p to the axis-aligned box [lo, hi] (0 inside).
float point_box_distance_squared(glm::vec3 p, glm::vec3 lo, glm::vec3 hi);

}  // namespace sculpt::core
