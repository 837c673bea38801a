#include "sculpt/core/nurbs/influence.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <glm/geometric.hpp>

#include "nurbs_fixtures.h"
#include "sculpt/core/nurbs/punctual_constraint.h"

namespace sculpt::core::nurbs {
namespace {

ParameterZone circle(glm::dvec2 c, double r) {
  ParameterZone z;
  z.shape = ParameterZone::Shape::kCircle;
  z.centre = c;
  z.radius = r;
  return z;
}

ParameterZone star() {
  // A five-pointed star around (0.5, 0.5): not convex, star-shaped from its centre.
  ParameterZone z;
  z.shape = ParameterZone::Shape::kPolygon;
  for (int k = 0; k < 10; ++k) {
    const double a = k * 3.14159265358979 / 5.0;
    const double r = k % 2 == 0 ? 0.4 : 0.17;
    z.polygon.emplace_back(0.5 + r * std::cos(a), 0.5 + r * std::sin(a));
  }
  return z;
}

TEST(Influence, NaturalInfluenceIsTheMinimumNormPseudoInverseSolution) {
  // Equation (2) with f = R(u,v) against Eigen's pseudo-inverse of the 1 x n
  // system sum_ij R_ij m_ij = e, on a polynomial and a rational surface.
  const NurbsSurface sheet = example_sheet();
  const NurbsSurface cyl = test::quarter_cylinder(3.0, 5.0);
  test::Params rand(5);
  for (const NurbsSurface* s : {&sheet, &cyl}) {
    for (int trial = 0; trial < 10; ++trial) {
      const double u = rand(), v = rand();
      const glm::dvec3 target =
          evaluate(*s, u, v) + glm::dvec3(rand(-5, 5), rand(-5, 5), rand(-5, 5));
      NurbsSurface moved = *s;
      ASSERT_TRUE(apply_linear_constraint(moved, u, v, target, natural_influence(*s, u, v)).ok());
      const std::vector<double> r = rational_basis_dense(*s, u, v);
      Eigen::MatrixXd a(1, static_cast<Eigen::Index>(r.size()));
      for (size_t k = 0; k < r.size(); ++k)
        a(0, static_cast<Eigen::Index>(k)) = r[k];
      const Eigen::MatrixXd pinv = a.completeOrthogonalDecomposition().pseudoInverse();
      const glm::dvec3 e = target - evaluate(*s, u, v);
      Eigen::RowVector3d ev(e.x, e.y, e.z);
      const Eigen::MatrixXd m = pinv * ev;  // n x 3
      double worst = 0.0;
      for (size_t k = 0; k < r.size(); ++k) {
        const glm::dvec3 d = moved.points[k] - s->points[k];
        const auto row = static_cast<Eigen::Index>(k);
        worst = std::max(worst, glm::length(d - glm::dvec3(m(row, 0), m(row, 1), m(row, 2))));
      }
      EXPECT_LE(worst, 1e-12);
    }
  }
}

TEST(Influence, GaussianWidensTheNaturalInfluenceWithinItsRadius) {
  const NurbsSurface s = example_sheet();
  const double u = 0.52, v = 0.5;  // not on a knot: 4 x 4 basis functions act
  const std::vector<double> natural = natural_influence(s, u, v);
  const std::vector<double> g3 = gaussian_influence(s, u, v, 3.0);
  const std::vector<double> g6 = gaussian_influence(s, u, v, 6.0);
  auto support = [](const std::vector<double>& f) {
    return std::count_if(f.begin(), f.end(), [](double x) { return x > 0.0; });
  };
  EXPECT_EQ(support(natural), 16);
  EXPECT_GT(support(g3), support(natural));
  EXPECT_GT(support(g6), support(g3));
  EXPECT_EQ(*std::max_element(g3.begin(), g3.end()), 1.0);
  // Nothing further than the radius from the natural support moves.
  const RationalBasis r = rational_basis(s, u, v);
  for (int j = 0; j < s.count_v; ++j) {
    for (int i = 0; i < s.count_u; ++i) {
      const int di = std::max({0, r.first_i - i, i - (r.first_i + 3)});
      const int dj = std::max({0, r.first_j - j, j - (r.first_j + 3)});
      if (di * di + dj * dj > 9) {
        EXPECT_EQ(g3[static_cast<size_t>(s.index(i, j))], 0.0);
      }
    }
  }
  EXPECT_EQ(gaussian_influence(s, u, v, 0.0), natural);
}

TEST(Influence, ZoneIsZeroOutsideHighNearTheConstraintLowNearTheBorder) {
  const NurbsSurface s = refine_v(refine_u(example_sheet(), std::vector<double>{0.45, 0.55}),
                                  std::vector<double>{0.45, 0.55});
  const double u = 0.5, v = 0.5;
  for (const ParameterZone& zone : {circle({0.5, 0.5}, 0.3), star()}) {
    Result<std::vector<double>> f = zone_influence(s, u, v, zone);
    ASSERT_TRUE(f.ok()) << f.error().message();
    const std::vector<double> gu = greville_u(s), gv = greville_v(s);
    int inside = 0;
    for (int j = 0; j < s.count_v; ++j) {
      for (int i = 0; i < s.count_u; ++i) {
        const glm::dvec2 g(gu[static_cast<size_t>(i)], gv[static_cast<size_t>(j)]);
        const double rho = relative_radius(zone, {u, v}, g);
        const double value = (*f)[static_cast<size_t>(s.index(i, j))];
        if (rho >= 1.0) {
          EXPECT_EQ(value, 0.0);
        } else {
          EXPECT_GT(value, 0.0);
          ++inside;
        }
        EXPECT_LE(value, 1.0);
      }
    }
    EXPECT_EQ(inside, control_points_in_zone(s, u, v, zone));
    // Decreasing with the relative radius: compare along a ray.
    std::vector<std::pair<double, double>> by_rho;
    for (int k = 0; k < s.point_count(); ++k) {
      const int i = k % s.count_u, j = k / s.count_u;
      by_rho.emplace_back(relative_radius(zone, {u, v}, {gu[i], gv[j]}), (*f)[k]);
    }
    std::sort(by_rho.begin(), by_rho.end());
    for (size_t k = 1; k < by_rho.size(); ++k)
      EXPECT_LE(by_rho[k].second, by_rho[k - 1].second);
  }
}

TEST(Influence, ZoneWithoutAnInfluencingControlPointIsRefusedThenRefinementFixesIt) {
  const NurbsSurface s = example_sheet();
  // Between Greville images: no image inside a radius-0.02 circle.
  const double u = 0.5, v = 0.5;
  const ParameterZone tiny = circle({0.5, 0.5}, 0.02);
  Result<std::vector<double>> f = zone_influence(s, u, v, tiny);
  ASSERT_FALSE(f.ok());
  EXPECT_NE(f.error().message().find("holds no control point that influences"), std::string::npos);

  Result<NurbsSurface> refined = refine_in_zone(s, u, v, tiny, 4);
  ASSERT_TRUE(refined.ok()) << refined.error().message();
  EXPECT_GE(control_points_in_zone(*refined, u, v, tiny), 4);
  EXPECT_TRUE(zone_influence(*refined, u, v, tiny).ok());
  double worst = 0.0;
  for (int j = 0; j <= 30; ++j) {
    for (int i = 0; i <= 30; ++i) {
      worst = std::max(worst, glm::length(evaluate(s, i / 30.0, j / 30.0) -
                                          evaluate(*refined, i / 30.0, j / 30.0)));
    }
  }
  EXPECT_LE(worst, 1e-12);
  // A cap on the growth is reported, not exceeded.
  Result<NurbsSurface> capped = refine_in_zone(s, u, v, tiny, 1000, 400);
  ASSERT_FALSE(capped.ok());
  EXPECT_NE(capped.error().message().find("limit 400"), std::string::npos);
}

TEST(Influence, ZoneValidation) {
  EXPECT_FALSE(validate(circle({0.5, 0.5}, 0.1), {0.9, 0.9}).ok());
  EXPECT_TRUE(validate(star(), {0.5, 0.5}).ok());
  // From a point inside one arm the star is not star-shaped.
  const Status st = validate(star(), {0.85, 0.5});
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().message().find("not star-shaped"), std::string::npos);
  ParameterZone line;
  line.shape = ParameterZone::Shape::kPolygon;
  line.polygon = {{0, 0}, {1, 1}, {0.5, 0.5}};
  EXPECT_NE(validate(line, {0.2, 0.2}).error().message().find("zero area"), std::string::npos);
}

}  // namespace
}  // namespace sculpt::core::nurbs
