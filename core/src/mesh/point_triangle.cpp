// Closest point on a triangle by Voronoi regions (Ericson, Real-Time Collision
// Detection §5.1.5): the same region tests as Jones' CSR-5-95 projection, but
// ordered so that every region is decided from six dot products, with no
// square root and no division except in the region that wins. Slivers (see
// is_sliver) run the same tests in double precision.

#include "sculpt/core/mesh/point_triangle.h"

#include <algorithm>

#include <glm/geometric.hpp>

namespace sculpt::core {
namespace {

template <class V>
struct Closest {
  V point;
  TriangleFeature feature;
};

// Nearest point on segment [a, b]; a zero-length segment is its end point.
template <class V>
V closest_on_segment(V p, V a, V b) {
  using S = typename V::value_type;
  const V ab = b - a;
  const S len2 = glm::dot(ab, ab);
  if (len2 <= S(0)) return a;
  const S t = std::clamp(glm::dot(p - a, ab) / len2, S(0), S(1));
  return a + t * ab;
}

// The region tests, in float for most triangles and in double for slivers.
template <class V>
Closest<V> closest(V p, V a, V b, V c) {
  using S = typename V::value_type;
  const V ab = b - a, ac = c - a, ap = p - a;
  const S d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= S(0) && d2 <= S(0)) return {a, TriangleFeature::kVertexA};
  const V bp = p - b;
  const S d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= S(0) && d4 <= d3) return {b, TriangleFeature::kVertexB};
  const S vc = d1 * d4 - d3 * d2;
  // d1 - d3 = |ab|^2: when a == b every point passes the other tests of this
  // region, yet the triangle is the segment ac; the later regions find it.
  if (vc <= S(0) && d1 >= S(0) && d3 <= S(0) && d1 > d3) {
    const S v = d1 / (d1 - d3);
    return {a + v * ab, TriangleFeature::kEdgeAB};
  }
  const V cp = p - c;
  const S d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= S(0) && d5 <= d6) return {c, TriangleFeature::kVertexC};
  const S vb = d5 * d2 - d1 * d6;
  if (vb <= S(0) && d2 >= S(0) && d6 <= S(0)) {
    const S den = d2 - d6;
    const S w = den > S(0) ? d2 / den : S(0);
    return {a + w * ac, TriangleFeature::kEdgeCA};
  }
  const S va = d3 * d6 - d5 * d4;
  if (va <= S(0) && (d4 - d3) >= S(0) && (d5 - d6) >= S(0)) {
    const S den = (d4 - d3) + (d5 - d6);
    const S w = den > S(0) ? (d4 - d3) / den : S(0);
    return {b + w * (c - b), TriangleFeature::kEdgeBC};
  }
  const S sum = va + vb + vc;
  if (!(sum > S(0))) {
    // Degenerate (zero area): the nearest of the three edges.
    auto d2_to = [&](V q) { return glm::dot(p - q, p - q); };
    Closest<V> best{closest_on_segment(p, a, b), TriangleFeature::kEdgeAB};
    const V bc = closest_on_segment(p, b, c), ca = closest_on_segment(p, c, a);
    if (d2_to(bc) < d2_to(best.point)) best = {bc, TriangleFeature::kEdgeBC};
    if (d2_to(ca) < d2_to(best.point)) best = {ca, TriangleFeature::kEdgeCA};
    return best;
  }
  const S denom = S(1) / sum;
  const S v = vb * denom, w = vc * denom;
  return {a + ab * v + ac * w, TriangleFeature::kFace};
}

}  // namespace

ClosestPoint closest_point_on_triangle(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  if (is_sliver(b - a, c - a)) {
    const glm::dvec3 pd(p);
    const Closest<glm::dvec3> r = closest(pd, glm::dvec3(a), glm::dvec3(b), glm::dvec3(c));
    const glm::dvec3 d = pd - r.point;
    return ClosestPoint{glm::vec3(r.point), static_cast<float>(glm::dot(d, d)), r.feature};
  }
  const Closest<glm::vec3> r = closest(p, a, b, c);
  const glm::vec3 d = p - r.point;
  return ClosestPoint{r.point, glm::dot(d, d), r.feature};
}

float sliver_distance2(glm::vec3 p, glm::vec3 a, glm::vec3 ab, glm::vec3 ac) {
  const glm::dvec3 pd(p), ad(a);
  const Closest<glm::dvec3> r = closest(pd, ad, ad + glm::dvec3(ab), ad + glm::dvec3(ac));
  const glm::dvec3 d = pd - r.point;
  return static_cast<float>(glm::dot(d, d));
}

}  // namespace sculpt::core
