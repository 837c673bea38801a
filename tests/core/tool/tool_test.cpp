#include "sculpt/core/tool/tool.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

std::filesystem::path temp_path(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("sculpt_tool_test_" + name);
}

// Value at the pivot's voxel, and at the grid's corner.
void expect_full_centre_empty_corner(const Tool& t, const char* what) {
  const glm::ivec3 c(glm::round(t.pivot));
  EXPECT_EQ(t.density.at(c.x, c.y, c.z), 255) << what;
  EXPECT_EQ(t.density.at(0, 0, 0), 0) << what;
  const glm::ivec3 d = t.density.dims();
  EXPECT_EQ(t.density.at(d.x - 1, d.y - 1, d.z - 1), 0) << what;
}

TEST(Tool, BuiltInShapesHaveTheirSizeAndCentre) {
  const Tool sphere = make_sphere_tool(10.0f);
  expect_full_centre_empty_corner(sphere, "sphere");
  // Radius 10: the voxel 10 from the centre sits on the surface (127).
  const glm::ivec3 c(glm::round(sphere.pivot));
  EXPECT_NEAR(sphere.density.at(c.x + 10, c.y, c.z), 127, 1);
  EXPECT_EQ(sphere.density.at(c.x + 11, c.y, c.z), 0);
  EXPECT_EQ(sphere.density.dims(), glm::ivec3(23));

  const Tool cube = make_cube_tool(8.0f);
  expect_full_centre_empty_corner(cube, "cube");
  const Tool cylinder = make_cylinder_tool(4.0f, 16.0f);
  expect_full_centre_empty_corner(cylinder, "cylinder");
  EXPECT_GT(cylinder.density.dims().z, cylinder.density.dims().x);
  const Tool cone = make_cone_tool(6.0f, 12.0f);
  // Wide at the bottom, narrow at the top.
  const glm::ivec3 k(glm::round(cone.pivot));
  EXPECT_EQ(cone.density.at(k.x + 4, k.y, k.z - 5), 255);
  EXPECT_EQ(cone.density.at(k.x + 4, k.y, k.z + 5), 0);
  // The ring is hollow in the middle and full in its tube.
  const Tool ring = make_ring_tool(8.0f, 3.0f);
  const glm::ivec3 r(glm::round(ring.pivot));
  EXPECT_EQ(ring.density.at(r.x, r.y, r.z), 0);
  EXPECT_EQ(ring.density.at(r.x + 8, r.y, r.z), 255);
}

TEST(Tool, SavesAndLoadsWithItsPivot) {
  Tool t = make_cone_tool(5.0f, 7.0f);
  t.pivot = {1.25f, 2.5f, 3.75f};
  const auto path = temp_path("pivot.nrrd");
  ASSERT_TRUE(write_tool_nrrd(path, t).ok());
  auto back = read_tool_nrrd(path);
  ASSERT_TRUE(back.ok()) << back.error().message();
  EXPECT_TRUE(back->density == t.density);
  EXPECT_EQ(back->pivot, t.pivot);
  // It stays an ordinary NRRD volume for every other reader.
  auto plain = read_nrrd_u8(path);
  ASSERT_TRUE(plain.ok());
  EXPECT_TRUE(*plain == t.density);
  std::filesystem::remove(path);
}

TEST(Tool, PlainNrrdGetsItsCentreAsPivot) {
  const auto path = temp_path("plain.nrrd");
  ASSERT_TRUE(write_nrrd(path, sphere_density(16, 0.4f)).ok());
  auto t = read_tool_nrrd(path);
  ASSERT_TRUE(t.ok());
  EXPECT_EQ(t->pivot, glm::vec3(7.5f));
  std::filesystem::remove(path);
}

TEST(Tool, BadPivotLineIsReportedWithTheFileName) {
  const auto path = temp_path("bad.nrrd");
  {
    std::ofstream out(path, std::ios::binary);
    out << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 1 1 1\nencoding: raw\nsculpt_pivot:=1 "
           "2\n\n";
    out.put('\x7f');
  }
  auto t = read_tool_nrrd(path);
  ASSERT_FALSE(t.ok());
  EXPECT_NE(t.error().message().find(path.string()), std::string::npos) << t.error().message();
  EXPECT_NE(t.error().message().find("sculpt_pivot"), std::string::npos) << t.error().message();
  std::filesystem::remove(path);
}

// Reproducer from the hardening review: `sculpt rotate` of a tool whose
// pivot sat 1e30 voxels away wrote a volume of sizes 0 0 0 with exit 0.
TEST(Tool, PivotFarOutsideTheGridIsRefused) {
  const auto path = temp_path("far.nrrd");
  for (const char* pivot : {"1e30 0 0", "-3 0.5 0.5", "0.5 0.5 4"}) {
    {
      std::ofstream out(path, std::ios::binary);
      out << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 1 1 1\nencoding: raw\nsculpt_pivot:="
          << pivot << "\n\n";
      out.put('\x7f');
    }
    auto t = read_tool_nrrd(path);
    ASSERT_FALSE(t.ok()) << pivot;
    EXPECT_NE(t.error().message().find("farther than the grid's size"), std::string::npos)
        << t.error().message();
  }
  {
    std::ofstream out(path, std::ios::binary);
    out << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 1 1 1\nencoding: raw\nsculpt_pivot:=-1 2 "
           "0.5\n\n";
    out.put('\x7f');
  }
  EXPECT_TRUE(read_tool_nrrd(path).ok()) << "a pivot one grid size out is a tool's handle";
  std::filesystem::remove(path);
}

TEST(Tool, MirrorTwiceIsIdentityAndMovesThePivot) {
  Tool t = make_cone_tool(4.0f, 9.0f);
  t.pivot = {1.0f, 2.0f, 3.0f};
  const Tool m = mirror_tool(t, 2);
  const glm::ivec3 d = t.density.dims();
  EXPECT_EQ(m.pivot.z, static_cast<float>(d.z - 1) - 3.0f);
  EXPECT_EQ(m.density.at(2, 3, 0), t.density.at(2, 3, d.z - 1));
  const Tool back = mirror_tool(m, 2);
  EXPECT_TRUE(back.density == t.density);
  EXPECT_EQ(back.pivot, t.pivot);
}

TEST(Tool, ARegionOfASculptureBecomesATool) {
  const Volume v = sphere_volume(64, 0.3f);
  const Box region{glm::ivec3(10), glm::ivec3(40, 50, 60)};
  const Tool t = tool_from_volume(v, region);
  EXPECT_EQ(t.density.dims(), region.size());
  EXPECT_EQ(t.density.at(5, 7, 9), v.voxel(glm::ivec3(15, 17, 19)));
  EXPECT_EQ(t.pivot, grid_centre(region.size()));
}

// Hardness 1 is the tool as it was before hardness existed: the shape's
// density_from_distance() voxel by voxel, and a dab with it changes the
// material bit for bit as before.
TEST(ToolHardness, OneIsTodaysToolAndDabBitForBit) {
  for (float d = -20.0f; d <= 20.0f; d += 0.013f)
    ASSERT_EQ(tool_density(d, 12.0f, 1.0f), density_from_distance(d)) << d;
  const float r = 9.3f;
  const Tool hard = make_sphere_tool(r, 1.0f);
  // The ball as it was made before: density_from_distance of the distance
  // to the grid's centre.
  const glm::ivec3 dims = hard.density.dims();
  DenseGrid<uint8_t> before(dims);
  const glm::vec3 c = grid_centre(dims);
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x)
        before.at(x, y, z) = density_from_distance(glm::length(glm::vec3(x, y, z) - c) - r);
  EXPECT_EQ(hard.density.values(), before.values());
  EXPECT_EQ(make_cube_tool(7.0f).density.values(), make_cube_tool(7.0f, 1.0f).density.values());
  EXPECT_EQ(with_hardness(make_cone_tool(6.0f, 9.0f), 1.0f).density.values(),
            make_cone_tool(6.0f, 9.0f).density.values());
  // The dab: the same material from the tool as made before and at hardness 1.
  auto dab_with = [](Tool tool) {
    Volume v = sphere_volume(64, 0.3f);
    Sculptor s(v);
    s.set_tool(std::move(tool));
    (void)s.dab({{40.3f, 31.2f, 30.9f},
                 glm::normalize(glm::quat(0.9f, 0.2f, -0.3f, 0.1f)),
                 SculptMode::kSubtract,
                 0.8f});
    return v.content_hash();
  };
  EXPECT_EQ(dab_with(tool_from_grid(before)), dab_with(make_sphere_tool(r, 1.0f)));
}

TEST(Tool, AHardBallFillsItsInsideAndMeasuresOnlyItsRim) {
  // make_sphere_tool() at hardness 1 fills what lies deep inside and outside
  // and takes the distance only near the surface: the same bytes as every
  // voxel's density_from_distance, at radii from the smallest (no inside
  // deep enough to fill) to the bust's head ball, on odd and even grids.
  for (const float r : {0.5f, 1.0f, 1.7f, 2.0f, 2.5f, 3.01f, 12.8f, 40.3f, 66.0f, 110.0f}) {
    const Tool ball = make_sphere_tool(r);
    const glm::ivec3 dims = ball.density.dims();
    const glm::vec3 c = grid_centre(dims);
    int64_t filled = 0;
    for (int z = 0; z < dims.z; ++z)
      for (int y = 0; y < dims.y; ++y)
        for (int x = 0; x < dims.x; ++x) {
          const uint8_t want = density_from_distance(glm::length(glm::vec3(x, y, z) - c) - r);
          ASSERT_EQ(ball.density.at(x, y, z), want)
              << "radius " << r << " at " << x << " " << y << " " << z;
          filled += want == 255;
        }
    EXPECT_EQ(ball.sphere_radius_vox, r);
    if (r >= 12.0f) {
      EXPECT_GT(filled, 0) << r;
    }
  }
}

TEST(ToolHardness, SofterToolsTaperSmoothlyFromTheCentre) {
  const float r = 10.0f;
  int prev_max_step = 256;
  for (float hardness : {1.0f, 0.5f, 0.0f}) {
    const Tool t = make_sphere_tool(r, hardness);
    EXPECT_EQ(t.hardness, hardness);
    const glm::ivec3 c(glm::round(t.pivot));
    EXPECT_EQ(t.density.at(c.x, c.y, c.z), 255) << hardness;
    // Along a radius the density never rises and its steps shrink with the
    // hardness (hard: the 2-voxel rim, 127 a voxel).
    int max_step = 0;
    for (int x = c.x; x + 1 < t.density.dims().x; ++x) {
      const int a = t.density.at(x, c.y, c.z), b = t.density.at(x + 1, c.y, c.z);
      EXPECT_LE(b, a) << hardness << " at " << x;
      max_step = std::max(max_step, a - b);
    }
    EXPECT_LT(max_step, prev_max_step) << hardness;
    prev_max_step = max_step;
    // Nothing beyond the rim's outer edge.
    EXPECT_EQ(t.density.at(c.x + static_cast<int>(r) + 1, c.y, c.z), 0) << hardness;
  }
  // Hardness 0 tapers over the whole radius: 11 voxels from 255 to 0 in
  // steps of at most 255 * 1.5 / 11.
  EXPECT_LE(prev_max_step, 35);
}

TEST(ToolHardness, AnyToolSoftensFromItsOwnSurface) {
  // A ball held as a plain grid softens like the analytic ball.
  const Tool grid_ball = tool_from_grid(make_sphere_tool(9.0f).density);
  const Tool soft = with_hardness(grid_ball, 0.25f);
  const Tool analytic = make_sphere_tool(9.0f, 0.25f);
  ASSERT_EQ(soft.density.dims(), analytic.density.dims());
  int worst = 0;
  for (size_t i = 0; i < soft.density.size(); ++i)
    worst = std::max(worst, std::abs(int(soft.density[i]) - int(analytic.density[i])));
  EXPECT_LE(worst, 12);
  EXPECT_EQ(soft.hardness, 0.25f);
  // A make_sphere_tool() ball is re-made exactly.
  EXPECT_EQ(with_hardness(make_sphere_tool(9.0f), 0.25f).density.values(),
            analytic.density.values());
}

TEST(ToolHardness, OutOfRangeOrNotANumberIsAnError) {
  for (double h : {0.0, 0.3, 1.0})
    EXPECT_TRUE(check_hardness(h)) << h;
  for (double h : {-0.01, 1.01, std::nan(""), std::numeric_limits<double>::infinity()}) {
    const Status st = check_hardness(h);
    ASSERT_FALSE(st) << h;
    EXPECT_NE(st.error().message().find("hardness must be a number in [0, 1]"), std::string::npos)
        << st.error().message();
  }
}

}  // namespace
}  // namespace sculpt::core
