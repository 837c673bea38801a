#pragma once
// The linear punctual constraint of La Greca, Raffin & Gesquière §4.2: move
// the control points so that the deformed surface passes through `target`
// at the parameters (u, v), by equation (2):
//
//   m(i,j) = f(i,j) / (sum_kl R_kl(u,v) f(k,l)) * e,   e = target - S(u,v).
//
// Weights and knots do not change, so S'(u,v) = S(u,v) + e exactly (up to
// rounding). With f = R(u,v) (natural influence) the displacements are the
// minimum-norm solution of sum_ij R_ij m_ij = e, i.e. the pseudo-inverse.

#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/nurbs/nurbs_surface.h"

namespace sculpt::core::nurbs {

/// Displaces the control points of `surface` by equation (2) with the
/// influence `f` (one value >= 0 per control point). Returns the indices of
/// the control points that moved (f > 0), in increasing order; control points
/// with f = 0 are not touched. Fails, leaving the surface as it was, when f
/// has the wrong size or no control point with f > 0 influences (u, v).
Result<std::vector<int>> apply_linear_constraint(NurbsSurface& surface, double u, double v,
                                                 glm::dvec3 target, std::span<const double> f);

}  // namespace sculpt::core::nurbs
