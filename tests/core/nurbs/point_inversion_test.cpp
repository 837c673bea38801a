#include "sculpt/core/nurbs/point_inversion.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "nurbs_fixtures.h"

namespace sculpt::core::nurbs {
namespace {

TEST(PointInversion, SurfacePointsRoundTrip) {
  const NurbsSurface sheet = example_sheet();
  const NurbsSurface cyl = test::quarter_cylinder(3.0, 5.0);
  test::Params rand(3);
  for (const NurbsSurface* s : {&sheet, &cyl}) {
    for (int k = 0; k < 100; ++k) {
      const double u = rand(), v = rand();
      const SurfacePoint r = closest_point(*s, evaluate(*s, u, v));
      EXPECT_NEAR(r.u, u, 1e-9);
      EXPECT_NEAR(r.v, v, 1e-9);
      EXPECT_LT(r.distance, 1e-9);
    }
  }
}

TEST(PointInversion, OffSurfacePointFindsItsFootAlongTheNormal) {
  const NurbsSurface s = example_sheet();
  test::Params rand(4);
  for (int k = 0; k < 50; ++k) {
    const double u = rand(0.1, 0.9), v = rand(0.1, 0.9);
    const glm::dvec3 query = evaluate(s, u, v) + 2.0 * normal(s, u, v);
    const SurfacePoint r = closest_point(s, query);
    EXPECT_NEAR(r.u, u, 1e-8);
    EXPECT_NEAR(r.v, v, 1e-8);
    EXPECT_NEAR(r.distance, 2.0, 1e-8);
  }
}

TEST(PointInversion, OutsideTheDomainClampsToTheBorder) {
  const NurbsSurface s = flat_sheet(6, 5, 3, 2, 10.0, 8.0);
  const SurfacePoint r = closest_point(s, {-5.0, 4.0, 1.0});
  EXPECT_EQ(r.u, 0.0);
  EXPECT_NEAR(r.v, 0.5, 1e-12);
  EXPECT_NEAR(r.distance, std::sqrt(26.0), 1e-12);
}

TEST(PointInversion, CurvePointsRoundTrip) {
  const NurbsCurve c = test::quarter_circle(4.0);
  for (double t = 0.0; t <= 1.0; t += 0.1) {
    const CurvePoint r = closest_point(c, evaluate(c, t));
    EXPECT_NEAR(r.t, t, 1e-9);
    // A point off the circle, on its radius, projects radially.
    const glm::dvec3 p = evaluate(c, t);
    const CurvePoint off = closest_point(c, p * 1.5);
    EXPECT_NEAR(off.t, t, 1e-9);
    EXPECT_NEAR(off.distance, 2.0, 1e-9);
  }
}

}  // namespace
}  // namespace sculpt::core::nurbs
