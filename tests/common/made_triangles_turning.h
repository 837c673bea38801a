#pragma once
// Triangles a simplifier made whose normals turn further than a limit
// allows (core::NormalTurnLimit): what shows as a streak, a star or a wedge
// on the drawn clay. Counted independently of the simplifier: a triangle is
// "made" when no marched triangle has its three corners' positions.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <set>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "sculpt/core/mesh/mesh.h"

namespace sculpt::test {

/// Made by the simplifier, not kept as marched, and with two corners whose
/// normals are more than `max_deg` apart, or, along an edge longer than
/// `full_turn_length` (0: no such rule), `max_deg` times full_turn_length
/// over its length.
inline int64_t made_triangles_turning(const core::Mesh& marched, const core::Mesh& simplified,
                                      float max_deg, float full_turn_length = 0.0f) {
  using Corners = std::array<float, 9>;
  auto corners = [](const core::Mesh& m, const glm::uvec3& t, int first) {
    Corners c{};
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a)
        c[static_cast<size_t>(3 * k + a)] = m.positions[t[(first + k) % 3]][a];
    return c;
  };
  std::set<Corners> kept;
  for (const glm::uvec3& t : marched.triangles)
    for (int first = 0; first < 3; ++first)
      kept.insert(corners(marched, t, first));
  // A thousandth of a degree for float rounding near the bound.
  const double limit = static_cast<double>(max_deg) + 1e-3;
  auto edge_turns = [&](uint32_t a, uint32_t b) {
    const double deg = glm::degrees(std::acos(std::clamp(
        static_cast<double>(glm::dot(simplified.normals[a], simplified.normals[b])), -1.0, 1.0)));
    const double length = glm::distance(simplified.positions[a], simplified.positions[b]);
    return deg > limit || (full_turn_length > 0.0f && length > full_turn_length &&
                           deg * length > limit * full_turn_length);
  };
  int64_t turning = 0;
  for (const glm::uvec3& t : simplified.triangles) {
    const bool turns = edge_turns(t.x, t.y) || edge_turns(t.y, t.z) || edge_turns(t.x, t.z);
    turning += turns && !kept.contains(corners(simplified, t, 0));
  }
  return turning;
}

}  // namespace sculpt::test
