// Every method of Jones & Satherley §3 through the signed_distance front
// door: sign conventions, shell values, chamfer bounds, vector accuracy.

#include "sculpt/core/distance/signed_distance.h"

#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "sculpt/core/distance/brute_distance.h"
#include "sculpt/core/distance/distance_comparison.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

// A sphere off the grid: centre (12.3, 11.6, 12.1), radius 7.4, 25^3.
DenseGrid<uint8_t> off_grid_sphere(glm::vec3* centre, float* radius) {
  *centre = glm::vec3(12.3f, 11.6f, 12.1f);
  *radius = 7.4f;
  DenseGrid<uint8_t> g(glm::ivec3(25));
  for (int z = 0; z < 25; ++z)
    for (int y = 0; y < 25; ++y)
      for (int x = 0; x < 25; ++x)
        g.at(x, y, z) = density_from_distance(glm::length(glm::vec3(x, y, z) - *centre) - *radius);
  return g;
}

TEST(SignedDistance, SignIsNegativeInsideForEveryMethod) {
  glm::vec3 c;
  float r;
  const DenseGrid<uint8_t> g = off_grid_sphere(&c, &r);
  for (DistanceInit init : {DistanceInit::kBinary, DistanceInit::kShell})
    for (DistanceMethod m :
         {DistanceMethod::kBrute, DistanceMethod::kExact, DistanceMethod::kOctree,
          DistanceMethod::kChamferCity, DistanceMethod::kChamfer345, DistanceMethod::kChamfer5x5x5,
          DistanceMethod::kEvdt, DistanceMethod::kVcvdt}) {
      const DenseGrid<float> d = signed_distance(g, m, init, 2);
      for (size_t i = 0; i < g.size(); ++i) {
        if (g[i] > 127.5f) {
          ASSERT_LE(d[i], 0.0f) << distance_method_name(m) << " " << distance_init_name(init);
        } else {
          ASSERT_GE(d[i], 0.0f) << distance_method_name(m) << " " << distance_init_name(init);
        }
      }
      // The centre is deep inside, a corner far outside.
      EXPECT_LT(d.at(12, 12, 12), -5.0f) << distance_method_name(m);
      EXPECT_GT(d.at(0, 0, 0), 10.0f) << distance_method_name(m);
    }
}

TEST(SignedDistance, ExactAndOctreeEqualBrute) {
  glm::vec3 c;
  float r;
  const DenseGrid<uint8_t> g = off_grid_sphere(&c, &r);
  for (DistanceInit init : {DistanceInit::kBinary, DistanceInit::kShell}) {
    const DenseGrid<float> brute = signed_distance(g, DistanceMethod::kBrute, init, 2);
    const DenseGrid<float> octree = signed_distance(g, DistanceMethod::kOctree, init, 2);
    const DenseGrid<float> exact = signed_distance(g, DistanceMethod::kExact, init, 2);
    float worst = 0.0f;
    for (size_t i = 0; i < g.size(); ++i) {
      ASSERT_EQ(octree[i], brute[i]) << distance_init_name(init);
      worst = std::max(worst, std::abs(exact[i] - brute[i]));
    }
    // Binary: the same integer problem, exact. Shell: the hybrid is exact
    // in the shell and nearly so beyond it (signed_distance.cpp).
    if (init == DistanceInit::kBinary) {
      EXPECT_LT(worst, 1e-5f);
    } else {
      EXPECT_LT(worst, 0.15f);
    }
  }
}

// The hybrid measures to the triangulated surface itself, not to points of
// it sampled per voxel: against the exact distance to the triangulation it
// is off only near the medial axis (worst about 0.1 voxel at 40^3, mean
// about 1e-4), where the vector transform on the same shell is off by up to
// 0.28 everywhere (mean about 0.015).
TEST(SignedDistance, HybridExactMeasuresToTheTriangulatedSurface) {
  for (ComparisonShape shape : {ComparisonShape::kSphere, ComparisonShape::kTorus}) {
    const ComparisonInput in = comparison_input(shape, 40);
    const DistanceInput prepared =
        prepare_distance_input(level_function(in.density), DistanceInit::kShell, 2);
    const DenseGrid<float> truth =
        compute_signed_distance(prepared, DistanceMethod::kOctree, DistanceInit::kShell, 2);
    const DenseGrid<float> hybrid =
        compute_signed_distance(prepared, DistanceMethod::kExact, DistanceInit::kShell, 2);
    const DenseGrid<float> vector =
        compute_signed_distance(prepared, DistanceMethod::kVcvdt, DistanceInit::kShell, 2);
    double worst = 0.0, mean = 0.0, vector_mean = 0.0;
    size_t off = 0;
    for (size_t i = 0; i < truth.size(); ++i) {
      const double e = std::abs(double(hybrid[i]) - truth[i]);
      worst = std::max(worst, e);
      mean += e;
      off += e > 1e-4;
      vector_mean += std::abs(double(vector[i]) - truth[i]);
    }
    mean /= double(truth.size());
    vector_mean /= double(truth.size());
    EXPECT_LT(worst, 0.12) << in.name;
    EXPECT_LT(mean, 1e-3) << in.name;
    EXPECT_LT(off, truth.size() / 50) << in.name;  // under 2% of the voxels
    EXPECT_LT(20.0 * mean, vector_mean) << in.name;
  }
}

TEST(SignedDistance, ShellHoldsSubVoxelDistancesOnBothSides) {
  glm::vec3 c;
  float r;
  const DenseGrid<uint8_t> g = off_grid_sphere(&c, &r);
  const DistanceInput in = prepare_distance_input(level_function(g), DistanceInit::kShell, 1);
  const DistanceShell& s = *in.shell;
  const DenseGrid<float> ref = brute_distance_to_triangles(g.dims(), in.surface->triangles());
  int inner = 0, outer = 0, inside = 0, outside = 0;
  for (size_t k = 0; k < s.voxels.size(); ++k) {
    const size_t i = size_t(s.voxels[k]);
    EXPECT_FLOAT_EQ(std::abs(s.distance[k]), ref[i]);
    // Sub-voxel: within 0.12 of the true sphere. The density ramp is only 2
    // voxels wide (analytic_shapes.h), so along a tetrahedron's long edges
    // one end is clipped and the interpolated crossing moves by up to ~0.1.
    const glm::vec3 p(i % 25, (i / 25) % 25, i / 625);
    EXPECT_NEAR(s.distance[k], glm::length(p - c) - r, 0.12f);
    inner += s.membership[i] == DistanceShell::kInner;
    outer += s.membership[i] == DistanceShell::kOuter;
    (s.distance[k] < 0 ? inside : outside)++;
  }
  EXPECT_GT(inner, 0);
  EXPECT_GT(outer, 0);
  EXPECT_GT(inside, 0);
  EXPECT_GT(outside, 0);
  // S_n reaches 3 voxels beyond B at most: no shell voxel is farther than
  // 3 sqrt 3 + sqrt 3 from the surface.
  for (float v : s.distance)
    EXPECT_LT(std::abs(v), 7.0f);
}

TEST(SignedDistance, ChamferStaysWithinItsKnownBounds) {
  glm::vec3 c;
  float r;
  const DenseGrid<uint8_t> g = off_grid_sphere(&c, &r);
  const DenseGrid<float> e = signed_distance(g, DistanceMethod::kBrute, DistanceInit::kBinary, 2);
  const DenseGrid<float> city =
      signed_distance(g, DistanceMethod::kChamferCity, DistanceInit::kBinary);
  const DenseGrid<float> c345 =
      signed_distance(g, DistanceMethod::kChamfer345, DistanceInit::kBinary);
  const DenseGrid<float> c5 =
      signed_distance(g, DistanceMethod::kChamfer5x5x5, DistanceInit::kBinary);
  double err_city = 0, err_345 = 0, err_5 = 0;
  for (size_t i = 0; i < g.size(); ++i) {
    const float de = std::abs(e[i]);
    // City block: between the Euclidean and sqrt 3 times it.
    ASSERT_GE(std::abs(city[i]), de - 1e-4f);
    ASSERT_LE(std::abs(city[i]), std::sqrt(3.0f) * de + 1e-4f);
    // <3,4,5>/3: local weights at least 0.94 of the step lengths.
    ASSERT_GE(std::abs(c345[i]), 0.94f * de - 1e-4f);
    // Euclidean steps: never shorter than the straight line.
    ASSERT_GE(std::abs(c5[i]), de - 1e-4f);
    err_city += std::abs(std::abs(city[i]) - de);
    err_345 += std::abs(std::abs(c345[i]) - de);
    err_5 += std::abs(std::abs(c5[i]) - de);
  }
  // The bigger matrix is the better approximation.
  EXPECT_LT(err_345, err_city);
  EXPECT_LT(err_5, err_345);
}

TEST(SignedDistance, VectorTransformsAreNearlyExactOnTheShell) {
  glm::vec3 c;
  float r;
  const DenseGrid<uint8_t> g = off_grid_sphere(&c, &r);
  for (DistanceMethod m : {DistanceMethod::kEvdt, DistanceMethod::kVcvdt}) {
    const DenseGrid<float> d = signed_distance(g, m, DistanceInit::kShell, 1);
    double sum = 0;
    for (int z = 0; z < 25; ++z)
      for (int y = 0; y < 25; ++y)
        for (int x = 0; x < 25; ++x) {
          const float truth = glm::length(glm::vec3(x, y, z) - c) - r;
          ASSERT_NEAR(d.at(x, y, z), truth, 0.5f) << distance_method_name(m);
          sum += std::abs(d.at(x, y, z) - truth);
        }
    EXPECT_LT(sum / static_cast<double>(g.size()), 0.05) << distance_method_name(m);
  }
}

TEST(SignedDistance, NamesRoundTripAndUnknownNamesAreErrors) {
  for (const char* n : {"brute", "exact", "octree", "chamfer-city", "chamfer-345", "chamfer-5x5x5",
                        "evdt", "vcvdt"}) {
    auto m = parse_distance_method(n);
    ASSERT_TRUE(m.ok());
    EXPECT_STREQ(distance_method_name(*m), n);
  }
  EXPECT_FALSE(parse_distance_method("fast").ok());
  EXPECT_FALSE(parse_distance_init("grey").ok());
  EXPECT_TRUE(parse_distance_init("shell").ok());
}

}  // namespace
}  // namespace sculpt::core
