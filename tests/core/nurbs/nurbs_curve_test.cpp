#include "sculpt/core/nurbs/nurbs_curve.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "nurbs_fixtures.h"

namespace sculpt::core::nurbs {
namespace {

TEST(NurbsCurve, RationalQuarterCircleIsExact) {
  const NurbsCurve c = test::quarter_circle(7.0);
  ASSERT_TRUE(validate(c).ok());
  EXPECT_TRUE(c.rational());
  for (double t = 0.0; t <= 1.0; t += 0.05) {
    EXPECT_NEAR(glm::length(evaluate(c, t)), 7.0, 1e-12) << t;
  }
  EXPECT_NEAR(glm::length(evaluate(c, 0.0) - glm::dvec3(7, 0, 0)), 0.0, 1e-15);
  EXPECT_NEAR(glm::length(evaluate(c, 1.0) - glm::dvec3(0, 7, 0)), 0.0, 1e-15);
}

TEST(NurbsCurve, DerivativesMatchFiniteDifferencesAndCircleGeometry) {
  const NurbsCurve c = test::quarter_circle(2.0);
  for (double t : {0.1, 0.4, 0.77}) {
    const std::vector<glm::dvec3> d = derivatives(c, t, 2);
    ASSERT_EQ(d.size(), 3u);
    const double h = 1e-6;
    const glm::dvec3 fd = (evaluate(c, t + h) - evaluate(c, t - h)) / (2 * h);
    EXPECT_NEAR(glm::length(d[1] - fd), 0.0, 1e-7);
    const glm::dvec3 fd2 = (derivatives(c, t + h, 1)[1] - derivatives(c, t - h, 1)[1]) / (2 * h);
    EXPECT_NEAR(glm::length(d[2] - fd2), 0.0, 1e-5);
    // A circle's tangent is orthogonal to its radius.
    EXPECT_NEAR(glm::dot(d[0], d[1]), 0.0, 1e-12);
  }
}

TEST(NurbsCurve, KnotInsertionLeavesTheCurveUnchanged) {
  NurbsCurve c;
  c.degree = 3;
  c.knots = {0, 0, 0, 0, 0.3, 0.6, 1, 1, 1, 1};
  c.points = {{0, 0, 0}, {1, 2, 0}, {3, 3, 1}, {4, 0, 2}, {6, 1, 0}, {7, 3, 3}};
  c.weights = {1, 2, 0.5, 1, 3, 1};
  ASSERT_TRUE(validate(c).ok());
  const NurbsCurve once = insert_knot(c, 0.45);
  EXPECT_EQ(once.count(), 7);
  const NurbsCurve thrice = insert_knot(c, 0.3, 2);  // 0.3 reaches multiplicity 3
  EXPECT_EQ(thrice.count(), 8);
  const std::vector<double> many{0.1, 0.2, 0.2, 0.5, 0.8, 0.95};
  const NurbsCurve refined = refine(c, many);
  EXPECT_EQ(refined.count(), 12);
  for (const NurbsCurve* r : {&once, &thrice, &refined}) {
    ASSERT_TRUE(validate(*r).ok());
    double worst = 0.0;
    for (int k = 0; k <= 1000; ++k) {
      const double t = k / 1000.0;
      worst = std::max(worst, glm::length(evaluate(*r, t) - evaluate(c, t)));
    }
    EXPECT_LE(worst, 1e-12);
  }
}

TEST(NurbsCurve, StraightCurveIsLinearInItsParameter) {
  const glm::dvec3 a(1, 2, 3), b(-4, 5, 9);
  const NurbsCurve c = straight_curve(a, b, 3, 6);
  for (double t = 0.0; t <= 1.0; t += 0.125) {
    EXPECT_NEAR(glm::length(evaluate(c, t) - (a + t * (b - a))), 0.0, 1e-13);
  }
}

TEST(NurbsCurve, ValidationNamesTheField) {
  NurbsCurve c = test::quarter_circle(1.0);
  c.weights[1] = -1.0;
  ASSERT_FALSE(validate(c).ok());
  EXPECT_NE(validate(c).error().message().find("weights[1]"), std::string::npos);
  c.weights = {1, 1};
  EXPECT_NE(validate(c).error().message().find("expected 3 weights"), std::string::npos);
  c.weights.clear();
  c.knots = {0, 0, 1, 1, 1, 1};
  EXPECT_NE(validate(c).error().message().find("knots:"), std::string::npos);
}

}  // namespace
}  // namespace sculpt::core::nurbs
