#include "sculpt/station/view/tool_outline.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "sculpt/core/grid/dense_grid.h"
#include "sculpt/core/mesh/brick_simplify.h"
#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::station {
namespace {

// `density` averaged over blocks of `step`^3 voxels (the last blocks of a
// side over the voxels they hold), rounded to the nearest byte.
core::DenseGrid<uint8_t> averaged(const core::DenseGrid<uint8_t>& density, int step) {
  const glm::ivec3 d = density.dims();
  const glm::ivec3 c = (d + step - 1) / step;
  core::DenseGrid<uint8_t> out(c);
  for (int z = 0; z < c.z; ++z)
    for (int y = 0; y < c.y; ++y)
      for (int x = 0; x < c.x; ++x) {
        const glm::ivec3 lo = glm::ivec3(x, y, z) * step;
        const glm::ivec3 hi = glm::min(lo + step, d);
        int sum = 0, n = 0;
        for (int vz = lo.z; vz < hi.z; ++vz)
          for (int vy = lo.y; vy < hi.y; ++vy)
            for (int vx = lo.x; vx < hi.x; ++vx, ++n)
              sum += density.at(vx, vy, vz);
        out.at(x, y, z) = static_cast<uint8_t>((sum + n / 2) / n);
      }
  return out;
}

// Where a ball's density, falling outward, crosses the surface level
// (127.5): bisection over the signed distance from the ball's radius.
float surface_radius(const core::Tool& ball) {
  assert(ball.sphere_radius_vox > 0.0f);
  const float r = ball.sphere_radius_vox;
  float inside = -r, outside = 4.0f;
  for (int i = 0; i < 40; ++i) {
    const float mid = 0.5f * (inside + outside);
    (core::tool_density(mid, r, ball.hardness) > 127 ? inside : outside) = mid;
  }
  return r + 0.5f * (inside + outside);
}

// A sphere about `centre` with segments at most `edge` voxels long, a whole
// number of them round the equator, and half as many rings pole to pole.
core::Mesh uv_sphere(glm::vec3 centre, float radius, float edge) {
  constexpr float kPi = 3.14159265358979f;
  const int segments = std::clamp(static_cast<int>(std::ceil(2.0f * kPi * radius / edge)), 12, 256);
  const int rings = std::max(6, segments / 2);
  core::Mesh mesh;
  for (int i = 0; i <= rings; ++i) {
    const float polar = kPi * static_cast<float>(i) / static_cast<float>(rings);
    for (int j = 0; j <= segments; ++j) {
      // The seam's last column is its first again, to the bit: no crack.
      const float azimuth =
          2.0f * kPi * static_cast<float>(j % segments) / static_cast<float>(segments);
      const glm::vec3 n(std::sin(polar) * std::cos(azimuth), std::cos(polar),
                        std::sin(polar) * std::sin(azimuth));
      mesh.positions.push_back(centre + radius * n);
      mesh.normals.push_back(n);
    }
  }
  // Wound as the marching cubes wind the clay, outward faces counter-clockwise.
  const auto at = [&](int i, int j) { return static_cast<uint32_t>(i * (segments + 1) + j); };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      if (i > 0) mesh.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j)});
      if (i + 1 < rings) mesh.triangles.push_back({at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)});
    }
  return mesh;
}

}  // namespace

core::Mesh tool_outline(const core::Tool& tool, int max_cells) {
  const glm::ivec3 d = tool.density.dims();
  int step = 1;
  while (std::max({d.x, d.y, d.z}) > max_cells * step)
    step *= 2;
  const core::DenseGrid<uint8_t> cells = step == 1 ? tool.density : averaged(tool.density, step);
  // Two empty cells all round: a tool's grid ends where its density does
  // (a cube's faces lie on it), and the march closes no surface on the
  // volume's faces. An open outline draws as a shell from outside, but a
  // carving stand-in counts the faces it crosses and needs it closed.
  constexpr int kPad = 2;
  core::DenseGrid<uint8_t> padded(cells.dims() + 2 * kPad);
  for (int z = 0; z < cells.dims().z; ++z)
    for (int y = 0; y < cells.dims().y; ++y)
      for (int x = 0; x < cells.dims().x; ++x)
        padded.at(x + kPad, y + kPad, z + kPad) = cells.at(x, y, z);
  const core::Volume v = core::Volume::from_dense(padded);
  core::MarchingCubesOptions options;
  options.threads = 1;
  core::Mesh mesh = core::marching_cubes(v, 0, options);
  // Coarse voxel i stands for the block [i step, (i + 1) step), whose
  // centre is (step - 1) / 2 beyond its first voxel.
  const float offset = static_cast<float>(step - 1) * 0.5f;
  for (glm::vec3& p : mesh.positions)
    p = (p - static_cast<float>(kPad)) * static_cast<float>(step) + offset;
  return mesh;
}

core::Mesh ball_outline(const core::Tool& ball, bool coarse) {
  // A quad's diagonal, about 1.4 edges long, dips edge^2 / (4 radius)
  // inside the sphere at its middle: the edge that keeps it to the bound.
  const float radius = surface_radius(ball);
  const float error = coarse ? kCoarseBallErrorVox : kWindowBallErrorVox;
  return uv_sphere(ball.pivot, radius, std::sqrt(4.0f * radius * error));
}

core::Mesh drawn_outline(const core::Tool& tool, int max_cells) {
  // Closed, so simplifying keeps it closed (its topology is checked).
  core::BrickMesh marched;
  marched.mesh = tool_outline(tool, max_cells);
  return core::simplify_brick_mesh(marched, kDrawnOutlineErrorVox, core::BorderHold::kVertices)
      .brick.mesh;
}

core::Mesh window_tool_outline(const core::Tool& tool) {
  if (!(tool.sphere_radius_vox > 0.0f)) return drawn_outline(tool);
  return ball_outline(tool);
}

core::Mesh stand_in_outline(const core::Tool& tool, bool coarse) {
  if (tool.sphere_radius_vox > 0.0f) return ball_outline(tool, coarse);
  return drawn_outline(tool, coarse ? kToolOutlineCells : kStandInCells);
}

}  // namespace sculpt::station
