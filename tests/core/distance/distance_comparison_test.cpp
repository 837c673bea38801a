// The §3.7 comparison reproduces the paper's ordering of the methods.

#include "sculpt/core/distance/distance_comparison.h"

#include <gtest/gtest.h>

namespace sculpt::core {
namespace {

TEST(DistanceComparison, OrdersTheMethodsAsTheirTable1) {
  const ComparisonInput in = comparison_input(ComparisonShape::kSphere, 40);
  const auto rows = compare_distance_methods(in, default_comparison_cases(), 2);
  ASSERT_EQ(rows.size(), default_comparison_cases().size());
  auto mean = [&](DistanceMethod m, DistanceInit i) {
    for (const auto& r : rows)
      if (r.c.method == m && r.c.init == i) return r.mean_error;
    ADD_FAILURE() << "missing row";
    return 0.0;
  };
  using M = DistanceMethod;
  using I = DistanceInit;
  // Sub-voxel beats binary for every method.
  for (M m : {M::kExact, M::kChamferCity, M::kEvdt, M::kVcvdt})
    EXPECT_LT(mean(m, I::kShell), mean(m, I::kBinary));
  // VCVDT on the shell beats EVDT on binary data; chamfer is far behind.
  EXPECT_LT(mean(M::kVcvdt, I::kShell), mean(M::kEvdt, I::kBinary));
  EXPECT_GT(mean(M::kChamferCity, I::kShell), 5 * mean(M::kVcvdt, I::kShell));
  // Exact on the shell: sub-voxel accurate.
  EXPECT_LT(mean(M::kExact, I::kShell), 0.05);
  // Octree and exact agree on binary data (the same problem).
  EXPECT_NEAR(mean(M::kOctree, I::kBinary), mean(M::kExact, I::kBinary), 1e-6);
  EXPECT_NE(comparison_markdown(rows).find("| sphere | 40^3 | vcvdt | shell |"), std::string::npos);
}

}  // namespace
}  // namespace sculpt::core
