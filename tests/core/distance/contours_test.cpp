// Contour connection (§4.1): the branching stack becomes one closed surface.

#include "sculpt/core/distance/contours.h"

#include <gtest/gtest.h>

#include "sculpt/core/distance/distance_io.h"
#include "sculpt/core/mesh/marching_cubes.h"
#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core {
namespace {

const std::string kData = SCULPT_TEST_DATA_DIR "/distance/";

TEST(Contours, BranchingStackIsOneClosedSurface) {
  auto stack = read_contours(kData + "branching.contours");
  ASSERT_TRUE(stack.ok()) << stack.error().message();
  EXPECT_EQ(stack->contours.size(), 4u);
  const DenseGrid<float> d = contour_distance_field(*stack, 2);
  // One region at the trunk, two at the branches, none beyond the caps.
  EXPECT_LT(d.at(24, 24, 14), 0.0f);
  EXPECT_LT(d.at(14, 24, 30), 0.0f);
  EXPECT_LT(d.at(34, 24, 30), 0.0f);
  EXPECT_GT(d.at(24, 24, 30), 0.0f);
  EXPECT_GT(d.at(24, 24, 4), 0.0f);
  EXPECT_GT(d.at(24, 24, 36), 0.0f);
  const Mesh mesh = marching_cubes(Volume::from_dense(density_from_distance_field(d)));
  const MeshTopology t = check_topology(mesh);
  EXPECT_TRUE(t.manifold());
  EXPECT_EQ(component_count(mesh), 1);
  // A trunk splitting in two is still a sphere topologically.
  EXPECT_EQ(t.euler_characteristic(), 2);
}

TEST(Contours, ParseErrorsNameTheLine) {
  auto missing_end = read_contours(kData + "unclosed.contours");
  ASSERT_FALSE(missing_end.ok());
  EXPECT_NE(missing_end.error().message().find("unclosed.contours"), std::string::npos);
  EXPECT_NE(missing_end.error().message().find("no 'end'"), std::string::npos);
  auto header = parse_contours("dims 4 4 4\n");
  ASSERT_FALSE(header.ok());
  EXPECT_NE(header.error().message().find("line 1"), std::string::npos);
  auto slice = parse_contours("sculpt-contours 1\ndims 8 8 4\ncontour 9\n");
  ASSERT_FALSE(slice.ok());
  EXPECT_NE(slice.error().message().find("line 3"), std::string::npos);
  auto few = parse_contours("sculpt-contours 1\ndims 8 8 4\ncontour 1\n1 1\n2 2\nend\n");
  ASSERT_FALSE(few.ok());
  EXPECT_NE(few.error().message().find("fewer than 3"), std::string::npos);
  // A point outside its slice (the linear-time distance needs them inside),
  // and a grid too big for its float fields (2048^3 was 34 GB).
  auto outside = parse_contours("sculpt-contours 1\ndims 8 8 4\ncontour 1\n1 1\n9 2\n");
  ASSERT_FALSE(outside.ok());
  EXPECT_NE(outside.error().message().find("line 5: point outside the slice"), std::string::npos);
  auto huge = parse_contours("sculpt-contours 1\ndims 2048 2048 2048\n");
  ASSERT_FALSE(huge.ok());
  EXPECT_NE(huge.error().message().find("line 2: dims: more than"), std::string::npos);
}

}  // namespace
}  // namespace sculpt::core
