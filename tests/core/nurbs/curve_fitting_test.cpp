#include "sculpt/core/nurbs/curve_fitting.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include "nurbs_fixtures.h"
#include "sculpt/core/nurbs/point_inversion.h"

namespace sculpt::core::nurbs {
namespace {

std::vector<glm::dvec3> helix(int n, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> jitter(0.0, noise);
  std::vector<glm::dvec3> q;
  for (int k = 0; k < n; ++k) {
    const double a = 3.0 * k / (n - 1);
    q.emplace_back(10 * std::cos(a) + jitter(rng), 10 * std::sin(a) + jitter(rng),
                   4 * a + jitter(rng));
  }
  return q;
}

TEST(CurveFitting, InterpolationPassesThroughEveryPoint) {
  const std::vector<glm::dvec3> q = helix(12, 0.0, 1);
  for (int p : {1, 2, 3, 5}) {
    Result<NurbsCurve> c = interpolate_curve(q, p);
    ASSERT_TRUE(c.ok()) << c.error().message();
    ASSERT_TRUE(validate(*c).ok());
    EXPECT_EQ(c->count(), 12);
    for (const glm::dvec3& point : q)
      EXPECT_LT(closest_point(*c, point).distance, 1e-9);
    EXPECT_NEAR(glm::length(evaluate(*c, 0.0) - q.front()), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(evaluate(*c, 1.0) - q.back()), 0.0, 1e-12);
  }
}

TEST(CurveFitting, LeastSquaresFollowsNoisySamplesAndKeepsTheEnds) {
  const std::vector<glm::dvec3> noisy = helix(300, 0.05, 2);
  const std::vector<glm::dvec3> exact = helix(300, 0.0, 2);
  Result<NurbsCurve> c = fit_curve(noisy, 3, 12);
  ASSERT_TRUE(c.ok()) << c.error().message();
  ASSERT_TRUE(validate(*c).ok());
  EXPECT_EQ(c->count(), 12);
  EXPECT_EQ(evaluate(*c, 0.0), noisy.front());
  EXPECT_NEAR(glm::length(evaluate(*c, 1.0) - noisy.back()), 0.0, 1e-12);
  double worst = 0.0;
  for (const glm::dvec3& p : exact)
    worst = std::max(worst, closest_point(*c, p).distance);
  // Smoother than the noise (sigma 0.05 per axis), close to the helix.
  EXPECT_LT(worst, 0.15);
}

TEST(CurveFitting, BadInputIsRefusedWithAReason) {
  const std::vector<glm::dvec3> two{{0, 0, 0}, {1, 0, 0}};
  EXPECT_NE(interpolate_curve(two, 3).error().message().find("too few"), std::string::npos);
  const std::vector<glm::dvec3> repeated{{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  EXPECT_NE(interpolate_curve(repeated, 2).error().message().find("points 1 and 2 are equal"),
            std::string::npos);
  // A device at rest repeats points: fitting drops them.
  EXPECT_TRUE(fit_curve(repeated, 2, 3).ok());
  EXPECT_NE(fit_curve(repeated, 2, 4).error().message().find("distinct"), std::string::npos);
  EXPECT_NE(fit_curve(helix(20, 0, 1), 3, 3).error().message().find("too few"), std::string::npos);
  std::vector<glm::dvec3> nan = helix(20, 0, 1);
  nan[5].x = std::nan("");
  EXPECT_NE(fit_curve(nan, 3, 6).error().message().find("point 5"), std::string::npos);
}

}  // namespace
}  // namespace sculpt::core::nurbs
