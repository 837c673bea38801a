#pragma once
// Exact Euclidean distance from a point to a triangle (Jones & Satherley §3.2,
// the closest-point regions of Jones' CSR-5-95: the plane, an edge or a
// vertex). Coordinates in voxel units.

#include <cstdint>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
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

/// Whether triangle (a, a + ab, a + ac) is a sliver: its angle at a is under
/// about 6 degrees (sin^2 < 0.01), so that the region tests' differences of
/// products lose most of their float bits (up to 0.28 voxel of error on
/// marching-cubes slivers). Slivers are measured in double precision.
inline bool is_sliver(glm::vec3 ab, glm::vec3 ac) {
  const float ab2 = glm::dot(ab, ab), ac2 = glm::dot(ac, ac), abac = glm::dot(ab, ac);
  return ab2 * ac2 - abac * abac < 0.01f * ab2 * ac2;
}

/// triangle_distance2 in double precision, for slivers.
float sliver_distance2(glm::vec3 p, glm::vec3 a, glm::vec3 ab, glm::vec3 ac);

/// Squared distance from p to triangle (a, a + ab, a + ac): the region tests
/// of closest_point_on_triangle, inline and without the point, for the loops
/// that call it tens of millions of times (narrow band, hybrid transform).
/// May differ from closest_point_on_triangle's distance in the last bits.
inline float triangle_distance2(glm::vec3 p, glm::vec3 a, glm::vec3 ab, glm::vec3 ac) {
  if (is_sliver(ab, ac)) return sliver_distance2(p, a, ab, ac);
  const glm::vec3 ap = p - a;
  const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0f && d2 <= 0.0f) return glm::dot(ap, ap);
  const glm::vec3 bp = ap - ab;
  const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return glm::dot(bp, bp);
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f && d1 > d3) {  // d1 > d3: a != b
    const glm::vec3 q = ap - (d1 / (d1 - d3)) * ab;
    return glm::dot(q, q);
  }
  const glm::vec3 cp = ap - ac;
  const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return glm::dot(cp, cp);
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
    const float den = d2 - d6;
    const glm::vec3 q = ap - (den > 0.0f ? d2 / den : 0.0f) * ac;
    return glm::dot(q, q);
  }
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
    const float den = (d4 - d3) + (d5 - d6);
    const glm::vec3 q = bp - (den > 0.0f ? (d4 - d3) / den : 0.0f) * (ac - ab);
    return glm::dot(q, q);
  }
  const float sum = va + vb + vc;
  if (!(sum > 0.0f)) return point_triangle_distance_squared(p, a, a + ab, a + ac);
  const float inv = 1.0f / sum;
  const glm::vec3 q = ap - ab * (vb * inv) - ac * (vc * inv);
  return glm::dot(q, q);
}

/// Squared distance from p to the axis-aligned box [lo, hi] (0 inside).
inline float point_box_distance_squared(glm::vec3 p, glm::vec3 lo, glm::vec3 hi) {
  const glm::vec3 d = glm::max(glm::max(lo - p, p - hi), glm::vec3(0.0f));
  return glm::dot(d, d);
}

}  // namespace sculpt::core
