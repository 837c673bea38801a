#include "sculpt/core/nurbs/punctual_constraint.h"

#include <gtest/gtest.h>

#include <cstring>

#include <glm/geometric.hpp>

#include "nurbs_fixtures.h"
#include "sculpt/core/nurbs/influence.h"

namespace sculpt::core::nurbs {
namespace {

TEST(PunctualConstraint, EveryInfluenceMeetsTheTargetAndLeavesZeroInfluencePointsAlone) {
  const NurbsSurface sheet = refine_u(example_sheet(), std::vector<double>{0.4, 0.6});
  const NurbsSurface cyl = test::quarter_cylinder(3.0, 5.0);
  test::Params rand(6);
  ParameterZone zone;
  zone.radius = 0.35;
  for (const NurbsSurface* s : {&sheet, &cyl}) {
    for (int trial = 0; trial < 20; ++trial) {
      const double u = rand(0.3, 0.7), v = rand(0.3, 0.7);
      zone.centre = {u + 0.05, v - 0.05};
      const glm::dvec3 target =
          evaluate(*s, u, v) + glm::dvec3(rand(-20, 20), rand(-20, 20), rand(-20, 20));
      std::vector<std::vector<double>> influences{natural_influence(*s, u, v),
                                                  gaussian_influence(*s, u, v, 2.5)};
      if (Result<std::vector<double>> z = zone_influence(*s, u, v, zone)) influences.push_back(*z);
      for (const std::vector<double>& f : influences) {
        NurbsSurface m = *s;
        Result<std::vector<int>> moved = apply_linear_constraint(m, u, v, target, f);
        ASSERT_TRUE(moved.ok()) << moved.error().message();
        EXPECT_LT(glm::length(evaluate(m, u, v) - target), 1e-9);
        size_t next = 0;
        for (int k = 0; k < m.point_count(); ++k) {
          const bool listed = next < moved->size() && (*moved)[next] == k;
          next += listed;
          if (f[static_cast<size_t>(k)] == 0.0) {
            EXPECT_FALSE(listed);
            // Bit-identical, not merely close.
            EXPECT_EQ(std::memcmp(&m.points[static_cast<size_t>(k)],
                                  &s->points[static_cast<size_t>(k)], sizeof(glm::dvec3)),
                      0);
          } else {
            EXPECT_TRUE(listed);
          }
        }
        EXPECT_EQ(m.weights, s->weights);
      }
    }
  }
}

TEST(PunctualConstraint, RefusesAnInfluenceThatCannotMoveThePoint) {
  NurbsSurface s = example_sheet();
  std::vector<double> f(static_cast<size_t>(s.point_count()), 0.0);
  f[0] = 1.0;  // the corner does not act on S(0.5, 0.5)
  const NurbsSurface before = s;
  Result<std::vector<int>> r = apply_linear_constraint(s, 0.5, 0.5, {0, 0, 50}, f);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message().find("no control point"), std::string::npos);
  EXPECT_EQ(s.points, before.points);
  EXPECT_FALSE(apply_linear_constraint(s, 0.5, 0.5, {0, 0, 50}, std::vector<double>(3, 1.0)).ok());
}

}  // namespace
}  // namespace sculpt::core::nurbs
