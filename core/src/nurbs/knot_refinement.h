#pragma once
// Boehm knot refinement of one row of homogeneous control points (The NURBS
// Book A5.4), shared by curves and both directions of surfaces.

#include <span>
#include <vector>

#include <glm/vec4.hpp>

namespace sculpt::core::nurbs::detail {

/// Refines `knots` (degree p, points.size() functions) by the sorted
/// `inserted` values, all inside the open domain. Writes the new knot vector
/// to `new_knots` and the new homogeneous points to `out` (points.size() +
/// inserted.size() values).
void refine_row(int p, std::span<const double> knots, std::span<const glm::dvec4> points,
                std::span<const double> inserted, std::vector<double>& new_knots,
                std::vector<glm::dvec4>& out);

}  // namespace sculpt::core::nurbs::detail
