#include "sculpt/core/distance/surface_normals.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

#include "sculpt/core/distance/distance_normals.h"
#include "sculpt/core/distance/iso_triangulation.h"
#include "sculpt/core/distance/surface_index.h"

namespace sculpt::core {
namespace {

// The stencil reaches one voxel below and two above a vertex's cell; a
// margin of 4 keeps the region's clamped faces away from every vertex
// inside the volume, and leaves the surface there to search.
constexpr int kMargin = 4;
// Distances are needed within ~2 voxels of the surface: the search stops
// beyond this (the gradient there is clamped anyway).
constexpr int kSearchRadius = 4;

}  // namespace

void set_normals_from_surface_distance(const Volume& volume, Mesh& mesh) {
  if (mesh.positions.empty()) return;
  const auto [lo, hi] = mesh_bounds(mesh);
  const Box region =
      intersect(Box{glm::ivec3(glm::floor(lo)) - kMargin, glm::ivec3(glm::ceil(hi)) + kMargin + 1},
                Box{glm::ivec3(0), volume.dims()});
  if (region.empty()) return;
  const DenseGrid<float> phi = level_function(volume.read(region));
  const SurfaceIndex surface(phi, 1);
  const glm::ivec3 dims = phi.dims();

  // Signed distance at the stencil voxels only; the rest stay 0 and unread.
  DenseGrid<float> distance(dims, 0.0f);
  DenseGrid<uint8_t> known(dims, 0);
  auto compute = [&](glm::ivec3 v) {
    const size_t i = known.index(v.x, v.y, v.z);
    if (known[i]) return;
    known[i] = 1;
    const SurfaceIndex::Nearest n = surface.nearest(v, kSearchRadius);
    const float d = std::isfinite(n.distance_squared) ? std::sqrt(n.distance_squared)
                                                      : static_cast<float>(kSearchRadius);
    distance[i] = phi[i] < 0.0f ? -d : d;
  };
  const glm::vec3 origin(region.lo);
  for (const glm::vec3& p : mesh.positions) {
    const glm::ivec3 cell = glm::ivec3(glm::floor(p - origin));
    const glm::ivec3 a = glm::max(cell - 1, glm::ivec3(0));
    const glm::ivec3 b = glm::min(cell + 2, dims - 1);
    for (int z = a.z; z <= b.z; ++z)
      for (int y = a.y; y <= b.y; ++y)
        for (int x = a.x; x <= b.x; ++x)
          compute({x, y, z});
  }
  mesh.normals.resize(mesh.positions.size(), glm::vec3(0.0f));
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3 n = distance_normal(distance, mesh.positions[i] - origin);
    if (n != glm::vec3(0.0f)) mesh.normals[i] = n;
  }
}

}  // namespace sculpt::core
