#pragma once
// A zone drawn in the parameter space of a surface (La Greca et al. §4.2,
// Figures 9-10): a circle or a polygon star-shaped with respect to the
// constrained parameters (u, v). It gives every parameter point a relative
// radius rho: 0 at (u, v), 1 on the zone's border (measured along the ray
// from (u, v), which a star-shaped zone's border crosses once), > 1 outside.

#include <vector>

#include <glm/vec2.hpp>

#include "sculpt/base/result.h"

namespace sculpt::core::nurbs {

struct ParameterZone {
  enum class Shape { kCircle, kPolygon };
  Shape shape = Shape::kCircle;
  /// Circle: centre and radius in parameter units.
  glm::dvec2 centre{0.5, 0.5};
  double radius = 0.25;
  /// Polygon: vertices (u, v) in order (either orientation), at least 3.
  std::vector<glm::dvec2> polygon;
};

/// Checks the zone against the constrained parameters `uv`: finite values, a
/// positive radius or a polygon of >= 3 vertices with non-zero area, `uv`
/// strictly inside, and (polygon) star-shaped from `uv`, i.e. `uv` sees every
/// edge from its inner side. The error says which rule failed.
Status validate(const ParameterZone& zone, glm::dvec2 uv);

/// Relative radius of `point` seen from `uv` (see above); the zone must have
/// passed validate(zone, uv). Returns 0 at uv.
double relative_radius(const ParameterZone& zone, glm::dvec2 uv, glm::dvec2 point);

/// Parameter bounding box of the zone: (u_min, v_min), (u_max, v_max).
std::pair<glm::dvec2, glm::dvec2> bounds(const ParameterZone& zone);

}  // namespace sculpt::core::nurbs
