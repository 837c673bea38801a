#pragma once
// Rational B-spline (NURBS) tensor-product surfaces of any degrees on clamped
// knot vectors, in double precision (The NURBS Book A3.5, A3.6, A4.3, A4.4,
// A5.5), with the notation of La Greca, Raffin & Gesquière §4.1:
//
//   S(u,v) = sum_ij R_ij(u,v) P_ij,
//   R_ij = N_i,p(u) N_j,q(v) w_ij / sum_kl N_k,p(u) N_l,q(v) w_kl.
//
// Control points are stored u fastest: P_ij at points[i + count_u * j],
// i in [0, count_u), j in [0, count_v). Units are the caller's.

#include <array>
#include <span>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/nurbs/knot_vector.h"

namespace sculpt::core::nurbs {

struct NurbsSurface {
  int degree_u = 3;
  int degree_v = 3;
  int count_u = 0;
  int count_v = 0;
  /// count_u + degree_u + 1 clamped knots.
  std::vector<double> knots_u;
  /// count_v + degree_v + 1 clamped knots.
  std::vector<double> knots_v;
  /// count_u * count_v control points, u fastest.
  std::vector<glm::dvec3> points;
  /// One positive weight per control point (same order), or empty for all 1.
  std::vector<double> weights;

  int index(int i, int j) const { return i + count_u * j; }
  glm::dvec3& point(int i, int j) { return points[static_cast<size_t>(index(i, j))]; }
  const glm::dvec3& point(int i, int j) const { return points[static_cast<size_t>(index(i, j))]; }
  double weight(int k) const { return weights.empty() ? 1.0 : weights[static_cast<size_t>(k)]; }
  int point_count() const { return count_u * count_v; }
  bool rational() const;
  double u_min() const { return knots_u[static_cast<size_t>(degree_u)]; }
  double u_max() const { return knots_u[static_cast<size_t>(count_u)]; }
  double v_min() const { return knots_v[static_cast<size_t>(degree_v)]; }
  double v_max() const { return knots_v[static_cast<size_t>(count_v)]; }
};

/// Checks degrees, counts, both knot vectors, #points == count_u * count_v,
/// finite points, weights empty or one per point, finite and > 0. The error
/// names the field ("knots_v: knots[4] = 0.2 is below ..."), no file name.
Status validate(const NurbsSurface& surface);

/// S(u,v); parameters are clamped to the domain.
glm::dvec3 evaluate(const NurbsSurface& surface, double u, double v);

/// S and its partial derivatives up to second order (A3.6 + A4.4).
struct SurfaceDerivatives {
  glm::dvec3 s{0.0}, su{0.0}, sv{0.0}, suu{0.0}, suv{0.0}, svv{0.0};
};
/// Derivatives at (u,v); `order` 1 leaves the second derivatives zero.
SurfaceDerivatives derivatives(const NurbsSurface& surface, double u, double v, int order = 2);

/// Unit normal Su x Sv (normalised); where that vanishes (a collapsed edge)
/// the normal of a point nudged into the domain, and (0,0,1) as a last resort.
glm::dvec3 normal(const NurbsSurface& surface, double u, double v);

/// The rational basis R_ij(u,v) that is non-zero at (u,v): the (p+1)(q+1)
/// functions of control points i in [first_i, first_i + p], j in [first_j,
/// first_j + q]; values[a + (p+1) * b] is R_(first_i+a),(first_j+b). They sum
/// to 1 (partition of unity).
struct RationalBasis {
  int first_i = 0;
  int first_j = 0;
  int width_u = 0;  ///< degree_u + 1
  int width_v = 0;  ///< degree_v + 1
  std::vector<double> values;
};
RationalBasis rational_basis(const NurbsSurface& surface, double u, double v);

/// All count_u * count_v values R_ij(u,v) (zeros included), u fastest.
std::vector<double> rational_basis_dense(const NurbsSurface& surface, double u, double v);

/// The same surface with knots inserted (A5.5: Boehm refinement of every
/// row, in homogeneous coordinates). new_knots sorted, inside the domain.
NurbsSurface refine_u(const NurbsSurface& surface, std::span<const double> new_knots);
NurbsSurface refine_v(const NurbsSurface& surface, std::span<const double> new_knots);

/// Greville abscissae of each direction (count_u and count_v values).
std::vector<double> greville_u(const NurbsSurface& surface);
std::vector<double> greville_v(const NurbsSurface& surface);

/// A flat rectangular sheet in the plane z = 0, [0, size_x] x [0, size_y],
/// control points at their Greville images so S(u,v) = (u size_x, v size_y, 0)
/// exactly (linear precision). Uniform clamped knots on [0, 1].
NurbsSurface flat_sheet(int count_u, int count_v, int degree_u, int degree_v, double size_x,
                        double size_y);

/// The paper's test object (Figures 7, 14, 15): a 15 x 10 bicubic sheet of
/// size 140 x 90, gently waved in z so it is not planar.
NurbsSurface example_sheet();

/// Homogeneous control point (w x, w y, w z, w) of point k.
inline glm::dvec4 homogeneous(const NurbsSurface& s, int k) {
  const double w = s.weight(k);
  return {s.points[static_cast<size_t>(k)] * w, w};
}

}  // namespace sculpt::core::nurbs
