#pragma once
// Surfaces and curves the NURBS tests share: a polynomial waved sheet, a
// rational one (a quarter cylinder, exact circles along u), a quarter circle.

#include <cmath>
#include <random>

#include "sculpt/core/nurbs/nurbs_curve.h"
#include "sculpt/core/nurbs/nurbs_surface.h"

namespace sculpt::core::nurbs::test {

/// Quarter circle of radius r in the xy plane, degree 2, exactly rational.
inline NurbsCurve quarter_circle(double r) {
  NurbsCurve c;
  c.degree = 2;
  c.knots = {0, 0, 0, 1, 1, 1};
  c.points = {{r, 0, 0}, {r, r, 0}, {0, r, 0}};
  c.weights = {1.0, std::sqrt(0.5), 1.0};
  return c;
}

/// A quarter cylinder of radius r and height h (u around, v along z),
/// refined along v so it has interior knots: degree 2 x 3, 3 x 6 points.
inline NurbsSurface quarter_cylinder(double r, double h) {
  NurbsSurface s;
  s.degree_u = 2;
  s.degree_v = 3;
  s.count_u = 3;
  s.count_v = 6;
  s.knots_u = {0, 0, 0, 1, 1, 1};
  s.knots_v = uniform_clamped_knots(3, 6);
  const std::vector<double> gv = greville_abscissae(s.knots_v, 3);
  const glm::dvec3 ring[3] = {{r, 0, 0}, {r, r, 0}, {0, r, 0}};
  const double w[3] = {1.0, std::sqrt(0.5), 1.0};
  for (int j = 0; j < 6; ++j) {
    for (int i = 0; i < 3; ++i) {
      s.points.push_back(ring[i] + glm::dvec3(0, 0, h * gv[static_cast<size_t>(j)]));
      s.weights.push_back(w[i]);
    }
  }
  return s;
}

/// Uniform random parameters in [lo, hi].
class Params {
 public:
  explicit Params(unsigned seed) : rng_(seed) {}
  double operator()(double lo = 0.0, double hi = 1.0) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }

 private:
  std::mt19937 rng_;
};

}  // namespace sculpt::core::nurbs::test
