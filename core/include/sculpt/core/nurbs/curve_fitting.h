#pragma once
// Curves through or near sampled points (The NURBS Book chapter 9): global
// interpolation (A9.1) and least-squares approximation with fixed end points
// (A9.7), both with chord-length parameters. The station turns the device's
// noisy path into the path curve of a deformation with fit_curve().
//
// The curves are polynomial (weights 1), clamped, on the domain [0, 1].

#include <span>

#include <glm/vec3.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/nurbs/nurbs_curve.h"

namespace sculpt::core::nurbs {

/// The degree-`degree` curve through every point, C(t_k) = points[k] with
/// chord-length t_k; knots by averaging (Eq. 9.8). Needs at least degree + 1
/// points and no two consecutive points equal (the error says which).
Result<NurbsCurve> interpolate_curve(std::span<const glm::dvec3> points, int degree);

/// The degree-`degree` curve with `control_points` control points closest in
/// the least-squares sense to `points`, passing exactly through the first
/// and the last (A9.7, knots by Eq. 9.69). Needs degree + 1 <= control_points
/// <= points.size(); with equality it interpolates. Consecutive equal points
/// (a device at rest) are dropped first.
Result<NurbsCurve> fit_curve(std::span<const glm::dvec3> points, int degree, int control_points);

}  // namespace sculpt::core::nurbs
