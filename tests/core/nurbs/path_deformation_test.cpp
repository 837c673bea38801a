#include "sculpt/core/nurbs/path_deformation.h"

#include <gtest/gtest.h>

#include <cstring>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "nurbs_fixtures.h"
#include "sculpt/core/nurbs/curve_fitting.h"
#include "sculpt/core/nurbs/influence.h"

namespace sculpt::core::nurbs {
namespace {

bool same_bits(glm::dvec3 a, glm::dvec3 b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// An arch from S(u,v): up, over and down to the side.
NurbsCurve arch(glm::dvec3 start) {
  NurbsCurve c;
  c.degree = 3;
  c.knots = uniform_clamped_knots(3, 5);
  c.points = {start, start + glm::dvec3(0, 0, 30), start + glm::dvec3(15, 0, 45),
              start + glm::dvec3(30, 5, 30), start + glm::dvec3(35, 10, 10)};
  return c;
}

struct Case {
  NurbsSurface surface;
  double u, v;
  std::vector<double> f;
};

Case zone_case() {
  ParameterZone zone;
  zone.centre = {0.5, 0.5};
  zone.radius = 0.3;
  Case c{refine_in_zone(example_sheet(), 0.5, 0.5, zone, 60).value(), 0.5, 0.5, {}};
  c.f = zone_influence(c.surface, c.u, c.v, zone).value();
  return c;
}

TEST(PathDeformation, DefaultStepCountIsTenTimesDegreeTimesControlPoints) {
  Case c = zone_case();
  const NurbsCurve path = arch(evaluate(c.surface, c.u, c.v));
  Result<PathDeformation> d = PathDeformation::from_curve(c.surface, c.u, c.v, c.f, path);
  ASSERT_TRUE(d.ok()) << d.error().message();
  EXPECT_EQ(d->step_count(), 10 * 3 * 5);
}

TEST(PathDeformation, LastStepMeetsTheConstraintAndZeroInfluencePointsNeverMove) {
  Case c = zone_case();
  const NurbsCurve path = arch(evaluate(c.surface, c.u, c.v));
  for (bool rotate : {true, false}) {
    PathOptions o;
    o.steps = 40;
    o.rotate = rotate;
    Result<PathDeformation> d = PathDeformation::from_curve(c.surface, c.u, c.v, c.f, path, o);
    ASSERT_TRUE(d.ok()) << d.error().message();
    size_t previous = SIZE_MAX;
    double turned = 0.0;
    while (!d->done()) {
      const PathStep step = d->step();
      EXPECT_EQ(step.step + 1, d->steps_done());
      if (!d->done()) {
        // Equation (3): L_k = {f >= k/(N-1)} shrinks as k grows.
        EXPECT_LE(step.moved.size(), previous);
        previous = step.moved.size();
        EXPECT_DOUBLE_EQ(step.threshold, step.step / 39.0);
        turned += step.angle_rad;
      }
      for (int k = 0; k < c.surface.point_count(); ++k) {
        if (c.f[static_cast<size_t>(k)] == 0.0) {
          ASSERT_TRUE(same_bits(d->surface().points[static_cast<size_t>(k)],
                                c.surface.points[static_cast<size_t>(k)]))
              << "step " << step.step << " point " << k;
        }
      }
    }
    EXPECT_EQ(d->steps_done(), 40);
    EXPECT_LT(glm::length(evaluate(d->surface(), c.u, c.v) - evaluate(path, 1.0)), 1e-9);
    EXPECT_LT(d->residual(), 1e-9);
    if (rotate) {
      EXPECT_GT(turned, 1.0);  // the arch turns by more than a radian
    } else {
      EXPECT_EQ(turned, 0.0);
    }
  }
}

TEST(PathDeformation, FollowsTheCurveRatherThanTheChord) {
  // The straight constraint (one linear step) and the path end at the same
  // point, but the path lifts the surface over the arch on the way.
  Case c = zone_case();
  const NurbsCurve path = arch(evaluate(c.surface, c.u, c.v));
  PathOptions o;
  o.steps = 60;
  Result<PathDeformation> d = PathDeformation::from_curve(c.surface, c.u, c.v, c.f, path, o);
  ASSERT_TRUE(d.ok());
  double highest = -1e9;
  while (!d->done()) {
    d->step();
    highest = std::max(highest, evaluate(d->surface(), c.u, c.v).z);
    if (!d->done()) {
      EXPECT_LT(d->residual(), 15.0);  // stays near C(k/N)
    }
  }
  EXPECT_GT(highest, evaluate(c.surface, c.u, c.v).z + 25.0);
}

TEST(PathDeformation, RotationsAreOrthonormalAndTurnOneSegmentOntoTheNext) {
  test::Params rand(7);
  for (int k = 0; k < 200; ++k) {
    const glm::dvec3 a(rand(-1, 1), rand(-1, 1), rand(-1, 1));
    const glm::dvec3 b(rand(-1, 1), rand(-1, 1), rand(-1, 1));
    double angle = 0.0;
    const glm::dmat3 r = rotation_between(a, b, &angle);
    const glm::dmat3 should_be_identity = glm::transpose(r) * r;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j)
        EXPECT_NEAR(should_be_identity[i][j], i == j ? 1.0 : 0.0, 1e-14);
    }
    EXPECT_NEAR(glm::determinant(r), 1.0, 1e-14);
    EXPECT_NEAR(glm::length(r * glm::normalize(a) - glm::normalize(b)), 0.0, 1e-12);
    EXPECT_NEAR(angle, std::acos(glm::dot(glm::normalize(a), glm::normalize(b))), 1e-7);
  }
  EXPECT_EQ(rotation_between({1, 0, 0}, {2, 0, 0}), glm::dmat3(1.0));
  EXPECT_EQ(rotation_between({0, 0, 0}, {2, 0, 0}), glm::dmat3(1.0));
}

TEST(PathDeformation, RefusesAPathNotStartingOnTheSurface) {
  Case c = zone_case();
  const NurbsCurve path = arch(evaluate(c.surface, c.u, c.v) + glm::dvec3(0, 0, 1));
  Result<PathDeformation> d = PathDeformation::from_curve(c.surface, c.u, c.v, c.f, path);
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.error().message().find("C(0) must be S(u, v)"), std::string::npos);
  NurbsCurve bad = arch(evaluate(c.surface, c.u, c.v));
  bad.knots[4] = 2.0;
  EXPECT_NE(PathDeformation::from_curve(c.surface, c.u, c.v, c.f, bad)
                .error()
                .message()
                .find("path: knots"),
            std::string::npos);
  EXPECT_FALSE(PathDeformation::from_curve(c.surface, 1.5, c.v, c.f, path).ok());
}

TEST(PathDeformation, LiveDevicePointsEndExactlyAtTheLastPoint) {
  Case c = zone_case();
  const NurbsCurve path = arch(evaluate(c.surface, c.u, c.v));
  Result<PathDeformation> d = PathDeformation::live(c.surface, c.u, c.v, c.f, 50);
  ASSERT_TRUE(d.ok());
  std::vector<glm::dvec3> samples;
  int applied = 0;
  for (int k = 1; k <= 50; ++k) {
    const glm::dvec3 p = evaluate(path, k / 50.0);
    samples.push_back(p);
    applied += d->push_point(p).has_value();
  }
  EXPECT_EQ(applied, 49);  // the last point waits for finish()
  const std::vector<PathStep> rest = d->finish();
  ASSERT_EQ(rest.size(), 1u);
  EXPECT_TRUE(d->done());
  EXPECT_LT(glm::length(evaluate(d->surface(), c.u, c.v) - samples.back()), 1e-9);
  // The same samples fitted into a curve drive the curve mode to the same end.
  std::vector<glm::dvec3> with_start{evaluate(c.surface, c.u, c.v)};
  with_start.insert(with_start.end(), samples.begin(), samples.end());
  Result<NurbsCurve> fitted = fit_curve(with_start, 3, 8);
  ASSERT_TRUE(fitted.ok());
  Result<PathDeformation> e = PathDeformation::from_curve(c.surface, c.u, c.v, c.f, *fitted);
  ASSERT_TRUE(e.ok()) << e.error().message();
  e->run();
  EXPECT_LT(glm::length(evaluate(e->surface(), c.u, c.v) - samples.back()), 1e-9);
}

}  // namespace
}  // namespace sculpt::core::nurbs
