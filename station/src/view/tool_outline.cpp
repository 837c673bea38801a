#include "sculpt/station/view/tool_outline.h"

#include <algorithm>

#include "sculpt/core/grid/dense_grid.h"
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

}  // namespace

core::Mesh tool_outline(const core::Tool& tool, int max_cells) {
  const glm::ivec3 d = tool.density.dims();
  int step = 1;
  while (std::max({d.x, d.y, d.z}) > max_cells * step)
    step *= 2;
  const core::Volume v =
      core::Volume::from_dense(step == 1 ? tool.density : averaged(tool.density, step));
  core::MarchingCubesOptions options;
  options.threads = 1;
  core::Mesh mesh = core::marching_cubes(v, 0, options);
  // Coarse voxel i stands for the block [i step, (i + 1) step), whose
  // centre is (step - 1) / 2 beyond its first voxel.
  const float offset = static_cast<float>(step - 1) * 0.5f;
  for (glm::vec3& p : mesh.positions)
    p = p * static_cast<float>(step) + offset;
  return mesh;
}

}  // namespace sculpt::station
