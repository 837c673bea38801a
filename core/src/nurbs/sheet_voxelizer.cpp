// Shell voxelisation by brute force over each brick's nearby triangles, with
// the distance module's exact point-to-triangle distance: the sheets the
// station builds have a few thousand triangles and a thin shell, so the
// per-brick triangle lists are short.

#include "sculpt/core/nurbs/sheet_voxelizer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "sculpt/core/mesh/point_triangle.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core::nurbs {

Box voxelize_shell(const Mesh& mesh, double thickness_vox, ShellMode mode, Volume& volume) {
  const double half = 0.5 * thickness_vox;
  const double reach = half + 1.0;  // beyond it the density is 0
  struct Tri {
    glm::vec3 a, b, c;
    glm::ivec3 lo, hi;  // voxel box within reach, half-open
  };
  std::vector<Tri> tris;
  tris.reserve(mesh.triangles.size());
  Box all{glm::ivec3(std::numeric_limits<int>::max()), glm::ivec3(std::numeric_limits<int>::min())};
  for (const glm::uvec3& t : mesh.triangles) {
    Tri tri{mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z], {}, {}};
    const glm::dvec3 lo = glm::dvec3(glm::min(glm::min(tri.a, tri.b), tri.c)) - reach;
    const glm::dvec3 hi = glm::dvec3(glm::max(glm::max(tri.a, tri.b), tri.c)) + reach;
    tri.lo = glm::ivec3(glm::ceil(lo));
    tri.hi = glm::ivec3(glm::floor(hi)) + 1;
    all.lo = glm::min(all.lo, tri.lo);
    all.hi = glm::max(all.hi, tri.hi);
    tris.push_back(tri);
  }
  const Box region = intersect(all, Box{glm::ivec3(0), volume.dims()});
  if (tris.empty() || region.empty()) return Box{};
  const int e = volume.brick_edge();
  std::vector<float> dist;
  volume.edit(region, [&](glm::ivec3 origin, std::span<uint8_t> voxels) {
    const Box brick = intersect(Box{origin, origin + glm::ivec3(e)}, region);
    if (brick.empty()) return;
    dist.assign(voxels.size(), std::numeric_limits<float>::infinity());  // squared
    bool touched = false;
    for (const Tri& t : tris) {
      const Box box = intersect(brick, Box{t.lo, t.hi});
      if (box.empty()) continue;
      touched = true;
      for (int z = box.lo.z; z < box.hi.z; ++z) {
        for (int y = box.lo.y; y < box.hi.y; ++y) {
          for (int x = box.lo.x; x < box.hi.x; ++x) {
            const glm::ivec3 l = glm::ivec3(x, y, z) - origin;
            float& d = dist[static_cast<size_t>((l.z * e + l.y) * e + l.x)];
            d = std::min(d, point_triangle_distance_squared(glm::vec3(x, y, z), t.a, t.b, t.c));
          }
        }
      }
    }
    if (!touched) return;
    for (size_t i = 0; i < voxels.size(); ++i) {
      if (!std::isfinite(dist[i])) continue;
      const uint8_t value = density_from_distance(std::sqrt(dist[i]) - static_cast<float>(half));
      voxels[i] = mode == ShellMode::kAdd ? std::max(voxels[i], value)
                                          : std::min(voxels[i], static_cast<uint8_t>(255 - value));
    }
  });
  return region;
}

}  // namespace sculpt::core::nurbs
