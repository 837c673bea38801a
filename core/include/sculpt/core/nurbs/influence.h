#pragma once
// The localisation constraint f(i, j) of a punctual constraint (La Greca et
// al. §4.2): one non-negative value per control point (count_u * count_v,
// u fastest), normalised so its maximum is 1. A control point with f = 0 does
// not move.
//
//  - natural:  f = R_ij(u, v), the rational basis at the constrained
//    parameters (equation (2) then gives the minimum-norm displacement);
//  - gaussian: the natural influence convolved, in control-point index
//    space, with a Gaussian of radius n (Figure 8): kernel exp(-d^2 / (2
//    sigma^2)), sigma = n / 3, cut at d > n (d in index units);
//  - zone:     f(i, j) = 1 - 3 rho^2 + 2 rho^3 (1 at (u, v), falling smoothly
//    to 0 on the border) where rho is the relative radius of the control
//    point's parametric image (its Greville abscissae) in the zone, and 0
//    outside (Figure 10).

#include <vector>

#include "sculpt/base/result.h"
#include "sculpt/core/nurbs/nurbs_surface.h"
#include "sculpt/core/nurbs/parameter_zone.h"

namespace sculpt::core::nurbs {

std::vector<double> natural_influence(const NurbsSurface& surface, double u, double v);

/// radius_index >= 0 (0 gives the natural influence).
std::vector<double> gaussian_influence(const NurbsSurface& surface, double u, double v,
                                       double radius_index);

/// Fails (naming the reason) if the zone is invalid for (u, v) or holds no
/// control point that influences (u, v) (sum_ij R_ij(u, v) f(i, j) == 0):
/// such a zone cannot move S(u, v); refine_in_zone() adds points.
Result<std::vector<double>> zone_influence(const NurbsSurface& surface, double u, double v,
                                           const ParameterZone& zone);

/// Number of control points whose parametric image lies inside the zone.
int control_points_in_zone(const NurbsSurface& surface, double u, double v,
                           const ParameterZone& zone);

/// Refinement (§4.2): while fewer than `min_points` control points have
/// their parametric image inside the zone, or none of them influences
/// (u, v), halves every knot span meeting the zone's bounding box, in both
/// directions (Boehm insertion, so the surface does not change). Stops with
/// an error if that needs more than `max_points` control points in total.
/// The zone must have passed validate(zone, {u, v}).
Result<NurbsSurface> refine_in_zone(const NurbsSurface& surface, double u, double v,
                                    const ParameterZone& zone, int min_points,
                                    int max_points = 250000);

/// sum_ij R_ij(u, v) f(i, j): the denominator of equation (2).
double influence_at(const NurbsSurface& surface, double u, double v,
                    const std::vector<double>& influence);

}  // namespace sculpt::core::nurbs
