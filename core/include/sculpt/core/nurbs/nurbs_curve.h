#pragma once
// Rational B-spline (NURBS) curves of any degree on clamped knot vectors, in
// double precision: evaluation, derivatives (The NURBS Book A2.1-A4.2), and
// Boehm knot insertion / refinement (A5.1, A5.4), which leave the curve
// unchanged.
//
// Units are the caller's (the station uses voxel units). A curve with all
// weights 1 is polynomial (a B-spline); empty `weights` means the same.

#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/base/result.h"

namespace sculpt::core::nurbs {

struct NurbsCurve {
  int degree = 3;
  /// points.size() + degree + 1 clamped, non-decreasing knots.
  std::vector<double> knots;
  /// Control points, #points.
  std::vector<glm::dvec3> points;
  /// One positive weight per control point, or empty for all 1.
  std::vector<double> weights;

  int count() const { return static_cast<int>(points.size()); }
  double weight(int i) const { return weights.empty() ? 1.0 : weights[static_cast<size_t>(i)]; }
  /// Whether any weight differs from 1.
  bool rational() const;
  double domain_min() const { return knots[static_cast<size_t>(degree)]; }
  double domain_max() const { return knots[points.size()]; }
};

/// Checks counts, knots (validate_knots) and weights (finite, > 0) and that
/// points are finite. The error names the field ("weights[3] = -1 is not
/// positive"), without a file name.
Status validate(const NurbsCurve& curve);

/// C(t); t is clamped to the domain.
glm::dvec3 evaluate(const NurbsCurve& curve, double t);

/// C and its derivatives up to `order` at t (A3.2 on the homogeneous curve,
/// then A4.2): result[k] = d^k C / dt^k, order + 1 vectors.
std::vector<glm::dvec3> derivatives(const NurbsCurve& curve, double t, int order);

/// The same curve with the knots `new_knots` (sorted, inside the domain)
/// inserted (Boehm / Oslo refinement, A5.4). Each knot's final multiplicity
/// must stay <= degree (asserted).
NurbsCurve refine(const NurbsCurve& curve, std::span<const double> new_knots);

/// The same curve with knot t inserted `times` times (A5.1 by refinement).
NurbsCurve insert_knot(const NurbsCurve& curve, double t, int times = 1);

/// A straight segment from a to b as a degree-`degree` curve with `count`
/// control points evenly spaced (linear precision makes C(t) = a + t (b - a)).
NurbsCurve straight_curve(glm::dvec3 a, glm::dvec3 b, int degree = 3, int count = 4);

}  // namespace sculpt::core::nurbs
