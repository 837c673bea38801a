// Closest point on a triangle by Voronoi regions (Ericson, Real-Time Collision
// Detection §5.1.5): the same region tests as Jones' CSR-5-95 projection, but
// ordered so that every region is decided from six dot products, with no
// square root and no division except in the region that wins.

#include "sculpt/core/distance/point_triangle.h"

#include <algorithm>

#include <glm/geometric.hpp>

namespace sculpt::core {
namespace {

ClosestPoint make(glm::vec3 p, glm::vec3 q, TriangleFeature f) {
  const glm::vec3 d = p - q;
  return ClosestPoint{q, glm::dot(d, d), f};
}

// Nearest point on segment [a, b]; a zero-length segment is its end point.
glm::vec3 closest_on_segment(glm::vec3 p, glm::vec3 a, glm::vec3 b) {
  const glm::vec3 ab = b - a;
  const float len2 = glm::dot(ab, ab);
  if (len2 <= 0.0f) return a;
  const float t = std::clamp(glm::dot(p - a, ab) / len2, 0.0f, 1.0f);
  return a + t * ab;
}

}  // namespace

ClosestPoint closest_point_on_triangle(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
  const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0f && d2 <= 0.0f) return make(p, a, TriangleFeature::kVertexA);
  const glm::vec3 bp = p - b;
  const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return make(p, b, TriangleFeature::kVertexB);
  const float vc = d1 * d4 - d3 * d2;
  // d1 - d3 = |ab|^2: when a == b every point passes the other tests of this
  // region, yet the triangle is the segment ac; the later regions find it.
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f && d1 > d3) {
    const float v = d1 / (d1 - d3);
    return make(p, a + v * ab, TriangleFeature::kEdgeAB);
  }
  const glm::vec3 cp = p - c;
  const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return make(p, c, TriangleFeature::kVertexC);
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
    const float den = d2 - d6;
    const float w = den > 0.0f ? d2 / den : 0.0f;
    return make(p, a + w * ac, TriangleFeature::kEdgeCA);
  }
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
    const float den = (d4 - d3) + (d5 - d6);
    const float w = den > 0.0f ? (d4 - d3) / den : 0.0f;
    return make(p, b + w * (c - b), TriangleFeature::kEdgeBC);
  }
  const float sum = va + vb + vc;
  if (!(sum > 0.0f)) {
    // Degenerate (zero area): the nearest of the three edges.
    ClosestPoint best = make(p, closest_on_segment(p, a, b), TriangleFeature::kEdgeAB);
    const ClosestPoint bc = make(p, closest_on_segment(p, b, c), TriangleFeature::kEdgeBC);
    const ClosestPoint ca = make(p, closest_on_segment(p, c, a), TriangleFeature::kEdgeCA);
    if (bc.distance_squared < best.distance_squared) best = bc;
    if (ca.distance_squared < best.distance_squared) best = ca;
    return best;
  }
  const float denom = 1.0f / sum;
  const float v = vb * denom, w = vc * denom;
  return make(p, a + ab * v + ac * w, TriangleFeature::kFace);
}

}  // namespace sculpt::core
