#include "sculpt/core/tool/tool_rotation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

// An asymmetric tool: a cone plus a noise pattern, so a wrong axis, sign or
// off-by-one shows.
Tool textured_tool(glm::ivec3 dims) {
  Tool t = tool_from_grid(DenseGrid<uint8_t>(dims));
  uint32_t s = 7;
  for (uint8_t& v : t.density.values()) {
    s = s * 1664525u + 1013904223u;
    v = static_cast<uint8_t>(s >> 24);
  }
  return t;
}

const glm::vec3 kAngles[] = {{30, 45, 60}, {10, -70, 200}, {0, 0, 33}, {90, 0, 0}, {123, 11, -47}};

TEST(ToolRotation, EulerXyzMatchesScipy) {
  // scipy.spatial.transform.Rotation.from_euler("xyz", [30, 45, 60], degrees=True).as_matrix()
  const double expected[3][3] = {{0.353553391, -0.573223305, 0.73919892},
                                 {0.612372436, 0.73919892, 0.280330086},
                                 {-0.707106781, 0.353553391, 0.612372436}};
  const glm::mat3 m = euler_xyz_deg({30, 45, 60});
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(m[c][r], expected[r][c], 1e-6) << "row " << r << " col " << c;
}

TEST(ToolRotation, BruteAndIncrementalAgreeExactly) {
  for (const Tool& t :
       {make_sphere_tool(6.3f), make_cone_tool(5.0f, 9.0f), textured_tool({9, 12, 7})}) {
    const PreparedTool tool(t);
    for (glm::vec3 angles : kAngles)
      for (glm::vec3 pos : {glm::vec3(0.0f), glm::vec3(3.25f, -1.7f, 0.5f)})
        for (Sampling s : {Sampling::kNearest, Sampling::kTrilinear}) {
          const glm::mat3 r = euler_xyz_deg(angles);
          const RotatedTool a = rotate_tool(tool, r, pos, RotationMethod::kBrute, s);
          const RotatedTool b = rotate_tool(tool, r, pos, RotationMethod::kIncremental, s);
          ASSERT_EQ(a.origin, b.origin);
          ASSERT_EQ(a.density.dims(), b.density.dims());
          EXPECT_TRUE(a.density == b.density)
              << "angles " << angles.x << "," << angles.y << "," << angles.z;
        }
  }
}

// Tools with a core (the ball round the pivot that rotation fills without
// sampling): a solid sphere (core 255, reach ball inside the padded grid), a
// grey cube whose core ends at the grid's border (outside reads 0), and a
// hollow shell (core 0). The brute-force method samples every voxel, so any
// core voxel that sampling would not give shows.
TEST(ToolRotation, CoreFillMatchesBruteForce) {
  // Large enough that its core rows reach the fill's minimum run (16).
  Tool grey = tool_from_grid(DenseGrid<uint8_t>({37, 37, 37}));
  for (uint8_t& v : grey.density.values())
    v = 200;
  Tool shell = make_sphere_tool(9.0f);
  const Tool inner = make_sphere_tool(5.0f);
  const glm::ivec3 shift = (shell.density.dims() - inner.density.dims()) / 2;
  for (int z = 0; z < inner.density.dims().z; ++z)
    for (int y = 0; y < inner.density.dims().y; ++y)
      for (int x = 0; x < inner.density.dims().x; ++x) {
        uint8_t& v = shell.density.at(x + shift.x, y + shift.y, z + shift.z);
        v = static_cast<uint8_t>(v - inner.density.at(x, y, z));
      }
  struct Case {
    Tool tool;
    uint8_t core_value;
    float min_core_vox;
  };
  for (const Case& c :
       {Case{make_sphere_tool(14.0f), 255, 10.0f}, Case{grey, 200, 9.0f}, Case{shell, 0, 1.0f}}) {
    const PreparedTool tool(c.tool);
    ASSERT_EQ(tool.core_value(), c.core_value);
    ASSERT_GT(tool.core_radius_vox(), c.min_core_vox);
    for (glm::vec3 angles : kAngles)
      for (glm::vec3 pos : {glm::vec3(0.0f), glm::vec3(3.25f, -1.7f, 0.5f)})
        for (Sampling s : {Sampling::kNearest, Sampling::kTrilinear}) {
          const glm::mat3 r = euler_xyz_deg(angles);
          const RotatedTool a = rotate_tool(tool, r, pos, RotationMethod::kBrute, s);
          const RotatedTool b = rotate_tool(tool, r, pos, RotationMethod::kIncremental, s);
          EXPECT_TRUE(a.density == b.density) << "core " << int{c.core_value} << " angles "
                                              << angles.x << "," << angles.y << "," << angles.z;
          // Row by row (the cache's path) gives the same voxels.
          const RotationFrame frame(tool, r, pos, s);
          const Box& box = frame.box();
          std::vector<uint8_t> row(static_cast<size_t>(box.size().x));
          for (int z = box.lo.z; z < box.hi.z; ++z)
            for (int y = box.lo.y; y < box.hi.y; ++y) {
              std::fill(row.begin(), row.end(), uint8_t{0});
              frame.sample_row(tool, y, z, box.lo.x, box.hi.x, row.data());
              for (int x = box.lo.x; x < box.hi.x; ++x)
                ASSERT_EQ(row[x - box.lo.x],
                          a.density.at(x - box.lo.x, y - box.lo.y, z - box.lo.z));
            }
        }
  }
}

// With the reach and core shortcuts off (the benchmarks' "Algorithm 1
// alone"), every voxel of the box is sampled by Algorithm 1's steps: the
// default result, bit for bit, for the built-in shapes (the ring's core is
// its hole, value 0), a tool whose reach ball leaves the padded grid (8^3
// trilinear) and an asymmetric one; both kernels, both samplings.
// The reach and core radii a prepared tool settles from a few voxels a row
// (each row's ends and the voxels nearest the pivot, found a word at a time)
// are those of testing every voxel: solid and hollow balls, a grey cube, a
// random tool, and pivots off the centre and outside the grid.
TEST(ToolRotation, PreparedRadiiAreEveryVoxelsBound) {
  Tool noise = tool_from_grid(DenseGrid<uint8_t>({23, 19, 21}));
  uint32_t seed = 7;
  for (uint8_t& v : noise.density.values()) {
    seed = seed * 1664525u + 1013904223u;
    v = (seed >> 24) < 40 ? static_cast<uint8_t>(seed >> 16) : 255;
  }
  Tool shell = make_sphere_tool(12.0f);
  for (uint8_t& v : shell.density.values())
    v = v == 255 ? 0 : v;
  Tool grey = tool_from_grid(DenseGrid<uint8_t>({37, 35, 33}, 200));
  std::vector<Tool> tools{make_sphere_tool(14.0f), make_sphere_tool(40.5f), shell, grey, noise};
  Tool moved = make_sphere_tool(20.0f);
  moved.pivot += glm::vec3(3.4f, -2.6f, 0.5f);
  tools.push_back(moved);
  Tool outside = noise;
  outside.pivot = glm::vec3(-4.0f, 9.0f, 30.0f);
  tools.push_back(outside);
  for (size_t t = 0; t < tools.size(); ++t) {
    const Tool& tool = tools[t];
    const PreparedTool prepared(tool);
    const DenseGrid<uint8_t>& g = tool.density;
    const glm::ivec3 d = g.dims();
    const glm::dvec3 pivot(tool.pivot);
    const glm::ivec3 centre(glm::floor(tool.pivot + 0.5f));
    const bool centred = g.in_bounds(centre.x, centre.y, centre.z);
    const uint8_t u = centred ? g.at(centre.x, centre.y, centre.z) : 0;
    ASSERT_EQ(prepared.core_value(), u) << "tool " << t;
    for (const Sampling s : {Sampling::kNearest, Sampling::kTrilinear}) {
      const double m = s == Sampling::kNearest ? 0.5 : 1.0;
      double reach2 = 0.0, other2 = centred ? 1e300 : 0.0;
      if (u != 0)  // outside the grid reads 0
        for (int i = 0; i < 3; ++i) {
          const double gap = std::max(0.0, std::min(pivot[i] + 1.0, d[i] - pivot[i]) - m);
          other2 = std::min(other2, gap * gap);
        }
      for (int z = 0; z < d.z; ++z)
        for (int y = 0; y < d.y; ++y)
          for (int x = 0; x < d.x; ++x) {
            const uint8_t v = g.at(x, y, z);
            const glm::dvec3 r = glm::abs(glm::dvec3(x, y, z) - pivot);
            if (v != 0) reach2 = std::max(reach2, glm::dot(r + m, r + m));
            if (v != u) {
              const glm::dvec3 near = glm::max(r - m, 0.0);
              other2 = std::min(other2, glm::dot(near, near));
            }
          }
      EXPECT_EQ(prepared.reach_vox(s), static_cast<float>(std::sqrt(reach2))) << "tool " << t;
      EXPECT_EQ(prepared.core_radius_vox(s), centred ? static_cast<float>(std::sqrt(other2)) : 0.0f)
          << "tool " << t;
    }
  }
}

TEST(ToolRotation, ClippingOffGivesTheDefaultResultBitForBit) {
  const Tool tools[] = {make_sphere_tool(9.0f),
                        make_cube_tool(13.0f),
                        make_cylinder_tool(6.5f, 13.0f),
                        make_ring_tool(9.0f, 3.0f),
                        tool_from_grid(sphere_density(8, 0.4f)),
                        textured_tool({9, 12, 7})};
  for (const Tool& t : tools) {
    const PreparedTool tool(t);
    for (bool vector : {false, true}) {
      (void)use_vector_kernel(vector);
      for (glm::vec3 angles : kAngles)
        for (glm::vec3 pos : {tool.pivot(), glm::vec3(3.25f, -1.7f, 0.5f)})
          for (Sampling s : {Sampling::kNearest, Sampling::kTrilinear}) {
            const glm::mat3 r = euler_xyz_deg(angles);
            const RotatedTool clipped = rotate_tool(tool, r, pos, RotationMethod::kIncremental, s);
            const RotatedTool whole =
                rotate_tool(tool, r, pos, RotationMethod::kIncremental, s, RotationClipping::kNone);
            ASSERT_EQ(clipped.origin, whole.origin);
            ASSERT_EQ(clipped.density.dims(), whole.density.dims());
            EXPECT_TRUE(clipped.density == whole.density)
                << "tool " << t.density.dims().x << "x" << t.density.dims().y << "x"
                << t.density.dims().z << " vector " << vector << " angles " << angles.x << ","
                << angles.y << "," << angles.z << " trilinear " << (s == Sampling::kTrilinear);
          }
    }
  }
  (void)use_vector_kernel(true);
}

TEST(ToolRotation, VectorAndScalarKernelsAgreeExactly) {
  const PreparedTool tool(textured_tool({21, 17, 23}));
  for (glm::vec3 angles : kAngles)
    for (Sampling s : {Sampling::kNearest, Sampling::kTrilinear}) {
      const glm::mat3 r = euler_xyz_deg(angles);
      (void)use_vector_kernel(false);
      const RotatedTool scalar =
          rotate_tool(tool, r, {1.3f, 2.7f, -0.4f}, RotationMethod::kIncremental, s);
      (void)use_vector_kernel(true);
      const RotatedTool vector =
          rotate_tool(tool, r, {1.3f, 2.7f, -0.4f}, RotationMethod::kIncremental, s);
      EXPECT_TRUE(scalar.density == vector.density);
    }
}

// A placement plans every row once (RotatedToolEntry), a plane at a time:
// each plan lies within the row's stretch within reach, cut to the tool's
// support where the reach ball leaves its grid, nothing outside it is
// non-zero, and sampling any stretch of the row by its plan gives the values
// that sampling it afresh gives.
TEST(ToolRotation, RowPlansSampleAsRowsSampledAfresh) {
  const PreparedTool sphere(make_sphere_tool(9.0f));
  // A long thin box: its reach ball (to the farthest corner) leaves the grid
  // across the thin sides, so most rows' plans are cut to the support.
  const PreparedTool slab(textured_tool({25, 7, 5}));
  std::mt19937 rng(7);
  int slab_rows = 0, slab_cut = 0;
  for (const PreparedTool* tool : {&sphere, &slab})
    for (glm::vec3 angles : kAngles) {
      const RotationFrame frame(*tool, euler_xyz_deg(angles), {0.3f, -2.6f, 1.0f},
                                Sampling::kTrilinear);
      const Box& box = frame.box();
      const glm::ivec3 size = box.size();
      std::vector<RotationFrame::RowPlan> plans(static_cast<size_t>(size.y));
      int rows = 0;
      for (int z = 0; z < size.z; ++z) {
        frame.row_plans(z, plans.data());
        for (int y = 0; y < size.y; ++y) {
          const RotationFrame::RowPlan p = plans[y];
          int x0 = 0, x1 = size.x;
          if (!frame.reach_span(y, z, x0, x1)) {
            ASSERT_EQ(p.x0, p.x1) << y << " " << z;
            continue;
          }
          ++rows;
          if (p.x0 < p.x1) {
            ASSERT_TRUE(p.x0 >= x0 && p.x1 <= x1) << y << " " << z;
            ASSERT_TRUE(p.x0 <= p.c0 && p.c0 <= p.c1 && p.c1 <= p.x1) << y << " " << z;
          }
          if (tool == &slab) {
            ++slab_rows;
            slab_cut += p.x1 - p.x0 < x1 - x0;
          }
          const int ty = box.lo.y + y, tz = box.lo.z + z;
          std::vector<uint8_t> afresh(static_cast<size_t>(size.x)), planned(afresh.size());
          frame.sample_row(*tool, ty, tz, box.lo.x, box.hi.x, afresh.data());
          for (int x = 0; x < size.x; ++x) {
            if (x < p.x0 || x >= p.x1) {
              ASSERT_EQ(afresh[x], 0) << x << " " << y << " " << z;
            }
          }
          // Two stretches of the row, as a stroke asks for its leading edge.
          const int a = std::uniform_int_distribution<int>(0, size.x)(rng);
          const int b = std::uniform_int_distribution<int>(a, size.x)(rng);
          frame.sample_row(*tool, ty, tz, box.lo.x, box.lo.x + a, p, planned.data());
          frame.sample_row(*tool, ty, tz, box.lo.x + a, box.lo.x + b, p, planned.data() + a);
          frame.sample_row(*tool, ty, tz, box.lo.x + b, box.hi.x, p, planned.data() + b);
          ASSERT_EQ(planned, afresh) << y << " " << z;
        }
      }
      EXPECT_GT(rows, size.y * size.z / 8);
    }
  EXPECT_GT(slab_cut, slab_rows / 4);
}

// The rows' stretches are planned eight rows at a time with AVX2 and one at
// a time otherwise, in the same float operations: the same stretches.
TEST(ToolRotation, VectorAndScalarPlanningGiveTheSameSpans) {
  const PreparedTool tool(make_sphere_tool(11.0f));
  for (glm::vec3 angles : kAngles)
    for (Sampling s : {Sampling::kNearest, Sampling::kTrilinear}) {
      const RotationFrame frame(tool, euler_xyz_deg(angles), {0.7f, 3.2f, -1.9f}, s);
      const glm::ivec3 size = frame.box().size();
      std::vector<int16_t> fields[2];
      for (int vector = 0; vector < 2; ++vector) {
        (void)use_vector_kernel(vector == 1);
        std::vector<RotationFrame::RowPlan> plans(static_cast<size_t>(size.y));
        for (int z = 0; z < size.z; ++z) {
          frame.row_plans(z, plans.data());
          for (const RotationFrame::RowPlan& p : plans)
            fields[vector].insert(fields[vector].end(), {p.x0, p.x1, p.c0, p.c1});
        }
      }
      (void)use_vector_kernel(true);
      EXPECT_EQ(fields[0], fields[1]);
      EXPECT_GT(std::count_if(fields[0].begin(), fields[0].end(), [](int16_t v) { return v > 0; }),
                0);
    }
}

TEST(ToolRotation, QuarterTurnsAreExact) {
  const Tool t = textured_tool({10, 10, 10});
  const PreparedTool tool(t);
  const int n = 10;
  for (Sampling s : {Sampling::kNearest, Sampling::kTrilinear}) {
    // 90 degrees about z sends (x, y) to (-y, x) about the centre.
    const RotatedTool z90 =
        rotate_tool_about_pivot(tool, euler_xyz_deg({0, 0, 90}), RotationMethod::kIncremental, s);
    ASSERT_EQ(z90.origin, glm::ivec3(0));
    ASSERT_EQ(z90.density.dims(), glm::ivec3(n));
    for (int z = 0; z < n; ++z)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
          ASSERT_EQ(z90.density.at(n - 1 - y, x, z), t.density.at(x, y, z));
    // 180 about x: (y, z) -> (-y, -z).
    const RotatedTool x180 =
        rotate_tool_about_pivot(tool, euler_xyz_deg({180, 0, 0}), RotationMethod::kBrute, s);
    ASSERT_EQ(x180.density.dims(), glm::ivec3(n));
    for (int z = 0; z < n; ++z)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
          ASSERT_EQ(x180.density.at(x, n - 1 - y, n - 1 - z), t.density.at(x, y, z));
  }
}

TEST(ToolRotation, RotationThenInverseReturnsTheToolWithinTrilinearBlur) {
  const Tool t = make_sphere_tool(8.0f);
  // Make it asymmetric so the round trip is not trivially the identity.
  Tool notched = t;
  for (int z = 0; z < 8; ++z)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x)
        notched.density.at(x, y, z) = 0;
  const glm::mat3 r = euler_xyz_deg({30, 45, 60});
  const RotatedTool there = rotate_tool_about_pivot(
      PreparedTool(notched), r, RotationMethod::kIncremental, Sampling::kTrilinear);
  const Tool turned{there.density, notched.pivot - glm::vec3(there.origin)};
  const RotatedTool back = rotate_tool(PreparedTool(turned), glm::transpose(r), notched.pivot,
                                       RotationMethod::kIncremental, Sampling::kTrilinear);
  const glm::ivec3 d = notched.density.dims();
  double sum = 0.0;
  int worst = 0;
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        const glm::ivec3 k = glm::ivec3(x, y, z) - back.origin;
        const int got = back.density.in_bounds(k.x, k.y, k.z) ? back.density.at(k.x, k.y, k.z) : 0;
        const int diff = std::abs(got - notched.density.at(x, y, z));
        sum += diff;
        worst = std::max(worst, diff);
      }
  const double mean = sum / static_cast<double>(voxel_count(d));
  // Two trilinear resamplings blur a 2-voxel ramp (and the notch's sharp
  // edges) by about half a voxel; a wrong inverse would move the notch.
  EXPECT_LT(mean, 6.0);
  EXPECT_LT(worst, 200);
}

TEST(ToolRotation, DirectMethodLeavesHolesInverseDoesNot) {
  const PreparedTool tool(make_sphere_tool(12.0f));
  const glm::mat3 r = euler_xyz_deg({30, 45, 60});
  const glm::vec3 pos(0.0f);
  const RotatedTool direct = rotate_tool_direct(tool, r, pos);
  const RotatedTool inverse =
      rotate_tool(tool, r, pos, RotationMethod::kIncremental, Sampling::kNearest);
  ASSERT_EQ(direct.origin, inverse.origin);
  auto holes = [&](const RotatedTool& rt) {
    int count = 0;
    const glm::ivec3 d = rt.density.dims();
    for (int z = 0; z < d.z; ++z)
      for (int y = 0; y < d.y; ++y)
        for (int x = 0; x < d.x; ++x) {
          const glm::vec3 k = glm::vec3(glm::ivec3(x, y, z) + rt.origin) - pos;
          if (glm::length(k) < 10.0f && rt.density.at(x, y, z) == 0) ++count;
        }
    return count;
  };
  EXPECT_GT(holes(direct), 0);
  EXPECT_EQ(holes(inverse), 0);
}

TEST(ToolRotation, BoxEnclosesTheRotatedToolAndIsTheToolAtIdentity) {
  const PreparedTool tool(make_cone_tool(6.0f, 10.0f));
  const RotatedTool id =
      rotate_tool_about_pivot(tool, glm::mat3(1.0f), RotationMethod::kBrute, Sampling::kNearest);
  EXPECT_EQ(id.origin, glm::ivec3(0));
  EXPECT_TRUE(id.density == tool.tool().density);
  // A box one voxel larger on every side holds nothing more.
  const glm::mat3 r = euler_xyz_deg({17, 71, -33});
  const RotationFrame frame(tool, r, {0.3f, 0.6f, 0.9f}, Sampling::kTrilinear);
  const Box& b = frame.box();
  int64_t inside = 0, outside = 0;
  for (int z = b.lo.z - 1; z <= b.hi.z; ++z)
    for (int y = b.lo.y - 1; y <= b.hi.y; ++y)
      for (int x = b.lo.x - 1; x <= b.hi.x; ++x) {
        const int v = frame.sample_voxel(tool, {x, y, z});
        (b.contains({x, y, z}) ? inside : outside) += v;
      }
  EXPECT_GT(inside, 0);
  EXPECT_EQ(outside, 0);
}

TEST(ToolRotation, SubVoxelPositionMovesTheRotatedMass) {
  const PreparedTool tool(make_sphere_tool(5.0f));
  const glm::mat3 r = euler_xyz_deg({30, 45, 60});
  auto centroid = [&](glm::vec3 pos) {
    const RotatedTool rt =
        rotate_tool(tool, r, pos, RotationMethod::kIncremental, Sampling::kTrilinear);
    glm::dvec3 c(0.0);
    double m = 0.0;
    const glm::ivec3 d = rt.density.dims();
    for (int z = 0; z < d.z; ++z)
      for (int y = 0; y < d.y; ++y)
        for (int x = 0; x < d.x; ++x) {
          const double v = rt.density.at(x, y, z);
          c += v * glm::dvec3(glm::ivec3(x, y, z) + rt.origin);
          m += v;
        }
    return c / m;
  };
  const glm::dvec3 a = centroid({10.0f, 10.0f, 10.0f});
  const glm::dvec3 b = centroid({10.25f, 10.5f, 10.75f});
  EXPECT_NEAR(b.x - a.x, 0.25, 0.03);
  EXPECT_NEAR(b.y - a.y, 0.5, 0.03);
  EXPECT_NEAR(b.z - a.z, 0.75, 0.03);
}

}  // namespace
}  // namespace sculpt::core
