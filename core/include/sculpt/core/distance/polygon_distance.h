#pragma once
// The signed 2D distance of a slice's
// closed polygons (contours.cpp), in time linear in the slice's pixels and
// the polygons' size. Negative inside by the even-odd rule.
//
// Written per pixel against every edge, a slice cost pixels x edges: a
// 2048^2 slice with a 100,000-point contour (a 2 MB file) was 4e11 distance
// evaluations. Here:
//   - the sign comes from scanlines: each row's edge crossings, sorted;
//   - pixels within kExactBand of an edge get the exact distance to the
//     nearest edge, found by visiting each edge's own neighbourhood;
//   - every other pixel takes the edge of its nearest exact pixel (a linear
//     feature transform, Felzenszwalb & Huttenlocher's lower envelope with
//     the argument kept) and its exact distance to that edge.
// So the zero level and everything within kExactBand of it are exact; farther
// out a value can exceed the true distance by at most sqrt(2) pixels (the
// nearest exact pixel's edge need not be the nearest edge), which moves no
// surface: the stack's 3D field is recomputed exactly from the zero level.

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

namespace sculpt::core {

/// Pixels at most this far from an edge (pixels) get the exact distance.
inline constexpr float kExactBand = 2.0f;

/// What the work cost, for the tests' complexity bounds.
struct PolygonDistanceCost {
  int64_t edge_distances = 0;  ///< point-to-edge distances evaluated
  int64_t crossings = 0;       ///< scanline crossings sorted
};

/// The signed distance of pixel (x, y) (centres at integers) to the closed
/// polygons, x fastest, dims.x * dims.y values. Vertices must lie in
/// [0, dims - 1].
std::vector<float> polygon_signed_distance(
    glm::ivec2 dims, const std::vector<const std::vector<glm::vec2>*>& polygons,
    PolygonDistanceCost* cost = nullptr);

}  // namespace sculpt::core
