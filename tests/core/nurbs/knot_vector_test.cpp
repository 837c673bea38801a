#include "sculpt/core/nurbs/knot_vector.h"

#include <gtest/gtest.h>

#include <vector>

#include "nurbs_fixtures.h"

namespace sculpt::core::nurbs {
namespace {

std::string message(const Status& st) {
  return st.ok() ? "" : st.error().message();
}

TEST(KnotVector, ValidationNamesTheRuleBroken) {
  EXPECT_TRUE(validate_knots(std::vector<double>{0, 0, 0, 0, 0.5, 1, 1, 1, 1}, 3, 5).ok());
  EXPECT_NE(message(validate_knots(std::vector<double>{0, 0, 0, 0, 1, 1, 1, 1}, 3, 5))
                .find("expected 9 knots"),
            std::string::npos);
  EXPECT_NE(message(validate_knots(std::vector<double>{0, 0, 0, 0, 0.6, 0.4, 1, 1, 1, 1}, 3, 6))
                .find("knots[5] = 0.4 is below knots[4] = 0.6"),
            std::string::npos);
  EXPECT_NE(message(validate_knots(std::vector<double>{0, 0, 0, 0.1, 0.5, 1, 1, 1, 1}, 3, 5))
                .find("not clamped"),
            std::string::npos);
  EXPECT_NE(message(validate_knots(std::vector<double>{0, 0, 0.5, 0.5, 0.5, 1, 1}, 1, 5))
                .find("repeated more than the degree"),
            std::string::npos);
  EXPECT_NE(message(validate_knots(std::vector<double>{1, 1, 1, 1}, 1, 2)).find("empty domain"),
            std::string::npos);
  EXPECT_NE(message(validate_knots(std::vector<double>{0, 0, 1, 1}, 0, 2)).find("degree 0"),
            std::string::npos);
  EXPECT_NE(message(validate_knots(std::vector<double>{0, 0, 0, 1, 1, 1}, 2, 2)).find("too few"),
            std::string::npos);
}

TEST(KnotVector, PartitionOfUnityAndNonNegativity) {
  test::Params rand(1);
  for (int p = 1; p <= 5; ++p) {
    std::vector<double> knots = uniform_clamped_knots(p, p + 6);
    if (p >= 2) knots[static_cast<size_t>(p + 2)] = knots[static_cast<size_t>(p + 3)];  // double
    ASSERT_TRUE(validate_knots(knots, p, p + 6).ok());
    for (int k = 0; k < 200; ++k) {
      const double t = k == 0 ? 0.0 : k == 1 ? 1.0 : rand();
      const int span = find_span(knots, p, p + 6, t);
      std::vector<double> n(static_cast<size_t>(p + 1));
      basis_functions(knots, p, span, t, n.data());
      double sum = 0.0;
      for (double x : n) {
        EXPECT_GE(x, 0.0);
        sum += x;
      }
      EXPECT_NEAR(sum, 1.0, 1e-14) << "p=" << p << " t=" << t;
    }
  }
}

TEST(KnotVector, DerivativesMatchFiniteDifferences) {
  const int p = 3;
  const std::vector<double> knots{0, 0, 0, 0, 0.2, 0.45, 0.7, 1, 1, 1, 1};
  const int count = 7;
  for (double t : {0.05, 0.3, 0.5, 0.69, 0.95}) {
    const int span = find_span(knots, p, count, t);
    std::vector<double> d(3 * (p + 1));
    basis_derivatives(knots, p, span, t, 2, d.data());
    const double h = 1e-6;
    std::vector<double> a(p + 1), b(p + 1), c(p + 1);
    basis_functions(knots, p, span, t - h, a.data());
    basis_functions(knots, p, span, t, b.data());
    basis_functions(knots, p, span, t + h, c.data());
    for (int j = 0; j <= p; ++j) {
      EXPECT_NEAR(d[static_cast<size_t>(j)], b[static_cast<size_t>(j)], 1e-15);
      EXPECT_NEAR(d[static_cast<size_t>(p + 1 + j)], (c[j] - a[j]) / (2 * h), 1e-6);
      EXPECT_NEAR(d[static_cast<size_t>(2 * (p + 1) + j)], (c[j] - 2 * b[j] + a[j]) / (h * h),
                  1e-2);
    }
  }
}

TEST(KnotVector, GrevilleLinearPrecision) {
  // sum_i g_i N_i(t) = t for every degree and knot vector.
  for (int p = 1; p <= 4; ++p) {
    std::vector<double> knots = uniform_clamped_knots(p, p + 5);
    knots[static_cast<size_t>(p + 1)] *= 0.3;  // non-uniform
    const std::vector<double> g = greville_abscissae(knots, p);
    ASSERT_EQ(g.size(), static_cast<size_t>(p + 5));
    EXPECT_EQ(g.front(), 0.0);
    EXPECT_EQ(g.back(), 1.0);
    for (double t = 0.0; t <= 1.0; t += 0.01) {
      const int span = find_span(knots, p, p + 5, t);
      std::vector<double> n(static_cast<size_t>(p + 1));
      basis_functions(knots, p, span, t, n.data());
      double x = 0.0;
      for (int j = 0; j <= p; ++j)
        x += g[static_cast<size_t>(span - p + j)] * n[static_cast<size_t>(j)];
      EXPECT_NEAR(x, t, 1e-14);
    }
  }
}

TEST(KnotVector, FindSpanAtEndsAndOutside) {
  const std::vector<double> knots{0, 0, 0, 0.5, 0.5, 1, 1, 1};
  EXPECT_EQ(find_span(knots, 2, 5, 0.0), 2);
  EXPECT_EQ(find_span(knots, 2, 5, 0.5), 4);
  EXPECT_EQ(find_span(knots, 2, 5, 0.49), 2);
  EXPECT_EQ(find_span(knots, 2, 5, 1.0), 4);
  EXPECT_EQ(find_span(knots, 2, 5, 7.0), 4);
  EXPECT_EQ(find_span(knots, 2, 5, -1.0), 2);
}

}  // namespace
}  // namespace sculpt::core::nurbs
