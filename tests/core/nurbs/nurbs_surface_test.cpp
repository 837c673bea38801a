#include "sculpt/core/nurbs/nurbs_surface.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "nurbs_fixtures.h"

namespace sculpt::core::nurbs {
namespace {

double max_difference(const NurbsSurface& a, const NurbsSurface& b) {
  double worst = 0.0;
  for (int j = 0; j <= 40; ++j) {
    for (int i = 0; i <= 40; ++i) {
      const double u = a.u_min() + (a.u_max() - a.u_min()) * i / 40.0;
      const double v = a.v_min() + (a.v_max() - a.v_min()) * j / 40.0;
      worst = std::max(worst, glm::length(evaluate(a, u, v) - evaluate(b, u, v)));
    }
  }
  return worst;
}

TEST(NurbsSurface, RationalBasisIsAPartitionOfUnity) {
  const NurbsSurface cyl = test::quarter_cylinder(3.0, 5.0);
  const NurbsSurface sheet = example_sheet();
  test::Params rand(2);
  for (const NurbsSurface* s : {&cyl, &sheet}) {
    ASSERT_TRUE(validate(*s).ok());
    for (int k = 0; k < 300; ++k) {
      const double u = rand(), v = rand();
      const std::vector<double> r = rational_basis_dense(*s, u, v);
      double sum = 0.0;
      glm::dvec3 p(0.0);
      for (size_t i = 0; i < r.size(); ++i) {
        EXPECT_GE(r[i], 0.0);
        sum += r[i];
        p += r[i] * s->points[i];
      }
      EXPECT_NEAR(sum, 1.0, 1e-14);
      EXPECT_NEAR(glm::length(p - evaluate(*s, u, v)), 0.0, 1e-12);
    }
  }
}

TEST(NurbsSurface, CylinderIsExactAndItsDerivativesMatchFiniteDifferences) {
  const NurbsSurface s = test::quarter_cylinder(3.0, 5.0);
  for (double u : {0.0, 0.2, 0.5, 0.9}) {
    for (double v : {0.1, 0.5, 0.8}) {
      const glm::dvec3 p = evaluate(s, u, v);
      EXPECT_NEAR(std::hypot(p.x, p.y), 3.0, 1e-12);
      EXPECT_NEAR(p.z, 5.0 * v, 1e-12);  // linear precision along v
      const SurfaceDerivatives d = derivatives(s, u, v, 2);
      const double h = 1e-5;
      auto fd_u = [&](auto f) { return (f(u + h, v) - f(u - h, v)) / (2 * h); };
      auto fd_v = [&](auto f) { return (f(u, v + h) - f(u, v - h)) / (2 * h); };
      auto S = [&](double a, double b) { return evaluate(s, a, b); };
      auto Su = [&](double a, double b) { return derivatives(s, a, b, 1).su; };
      auto Sv = [&](double a, double b) { return derivatives(s, a, b, 1).sv; };
      if (u > 0.0) {
        EXPECT_NEAR(glm::length(d.su - fd_u(S)), 0.0, 1e-7);
        EXPECT_NEAR(glm::length(d.suu - fd_u(Su)), 0.0, 1e-5);
        EXPECT_NEAR(glm::length(d.suv - fd_u(Sv)), 0.0, 1e-5);
      }
      EXPECT_NEAR(glm::length(d.sv - fd_v(S)), 0.0, 1e-7);
      EXPECT_NEAR(glm::length(d.svv - fd_v(Sv)), 0.0, 1e-5);
      // The normal of a cylinder points along the radius.
      const glm::dvec3 n = normal(s, u, v);
      EXPECT_NEAR(std::abs(glm::dot(n, glm::normalize(glm::dvec3(p.x, p.y, 0)))), 1.0, 1e-12);
    }
  }
}

TEST(NurbsSurface, KnotRefinementChangesTheSurfaceByAtMost1e12) {
  const NurbsSurface cyl = test::quarter_cylinder(3.0, 5.0);
  const NurbsSurface sheet = example_sheet();
  for (const NurbsSurface* s : {&cyl, &sheet}) {
    const std::vector<double> xu{0.13, 0.5, 0.5, 0.77};
    const std::vector<double> xv{0.05, 0.33, 0.6, 0.61, 0.99};
    const NurbsSurface ru = refine_u(*s, xu);
    const NurbsSurface rv = refine_v(ru, xv);
    ASSERT_TRUE(validate(rv).ok()) << validate(rv).error().message();
    EXPECT_EQ(rv.count_u, s->count_u + 4);
    EXPECT_EQ(rv.count_v, s->count_v + 5);
    EXPECT_EQ(rv.rational(), s->rational());
    EXPECT_LE(max_difference(*s, ru), 1e-12);
    EXPECT_LE(max_difference(*s, rv), 1e-12);
  }
}

TEST(NurbsSurface, FlatSheetHasLinearPrecisionAtGrevilleImages) {
  const NurbsSurface s = flat_sheet(15, 10, 3, 3, 140.0, 90.0);
  const std::vector<double> gu = greville_u(s), gv = greville_v(s);
  for (int j = 0; j < s.count_v; ++j) {
    for (int i = 0; i < s.count_u; ++i) {
      // The parametric image of P_ij is where the flat sheet meets P_ij.
      const glm::dvec3 p = evaluate(s, gu[static_cast<size_t>(i)], gv[static_cast<size_t>(j)]);
      EXPECT_NEAR(glm::length(p - s.point(i, j)), 0.0, 1e-12);
    }
  }
  EXPECT_NEAR(glm::length(evaluate(s, 0.3, 0.7) - glm::dvec3(42.0, 63.0, 0.0)), 0.0, 1e-12);
}

TEST(NurbsSurface, ValidationNamesTheField) {
  NurbsSurface s = example_sheet();
  s.points.pop_back();
  EXPECT_NE(validate(s).error().message().find("expected 150 control points"), std::string::npos);
  s = example_sheet();
  s.knots_v[5] = 0.9;
  EXPECT_NE(validate(s).error().message().find("knots_v"), std::string::npos);
  s = example_sheet();
  s.weights.assign(150, 1.0);
  s.weights[17] = 0.0;
  EXPECT_NE(validate(s).error().message().find("weights[17]"), std::string::npos);
  s = example_sheet();
  s.points[3].y = std::nan("");
  EXPECT_NE(validate(s).error().message().find("control_points[3]"), std::string::npos);
}

}  // namespace
}  // namespace sculpt::core::nurbs
