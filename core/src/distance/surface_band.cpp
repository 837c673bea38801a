#include "sculpt/core/distance/surface_band.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "sculpt/core/distance/surface_index.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {

DenseGrid<float> surface_band_distance(const DenseGrid<float>& phi, float half_width, int threads,
                                       Progress* progress) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const glm::ivec3 d = phi.dims();
  DenseGrid<float> out(d, kInf);
  for (size_t i = 0; i < out.size(); ++i)
    if (phi[i] < 0.0f) out[i] = -kInf;
  // Triangulating takes about a fifth of the time, the searches the rest.
  ProgressStage triangulating(progress, 0.0, 0.2, 1);
  const SurfaceIndex surface(phi, threads);
  if (!triangulating.step()) return out;
  const glm::ivec3 cells = surface.cell_dims();
  if (glm::any(glm::lessThanEqual(cells, glm::ivec3(0)))) return out;

  // The voxels that may lie within the band: a point of cell c (spanning
  // voxels c .. c + 1) is within `half_width` of voxel p only if p is in
  // [c - reach, c + 1 + reach] on every axis.
  const int reach = static_cast<int>(std::ceil(half_width));
  DenseGrid<uint8_t> near(d, 0);
  for (int z = 0; z < cells.z; ++z)
    for (int y = 0; y < cells.y; ++y)
      for (int x = 0; x < cells.x; ++x) {
        const auto [first, last] = surface.cell({x, y, z});
        if (first == last) continue;
        const glm::ivec3 lo = glm::max(glm::ivec3(x, y, z) - reach, glm::ivec3(0));
        const glm::ivec3 hi = glm::min(glm::ivec3(x, y, z) + 1 + reach, d - 1);
        for (int vz = lo.z; vz <= hi.z; ++vz)
          for (int vy = lo.y; vy <= hi.y; ++vy)
            std::memset(&near.at(lo.x, vy, vz), 1, static_cast<size_t>(hi.x - lo.x + 1));
      }

  // Rings up to reach + 1 hold every cell with a point nearer than
  // half_width (ring r's cells are all at least r - 1 away).
  const float band_squared = half_width * half_width;
  ProgressStage searching(progress, 0.2, 1.0, d.z);
  parallel_for(
      d.z,
      [&](int64_t z) {
        if (cancelled(progress)) return;
        for (int y = 0; y < d.y; ++y)
          for (int x = 0; x < d.x; ++x) {
            if (!near.at(x, y, static_cast<int>(z))) continue;
            const glm::ivec3 p(x, y, static_cast<int>(z));
            const SurfaceIndex::Nearest n = surface.nearest(p, reach + 1);
            if (n.distance_squared >= band_squared) continue;
            float& v = out.at(x, y, p.z);
            v = std::copysign(std::sqrt(n.distance_squared), v);
          }
        searching.step();
      },
      threads);
  return out;
}

}  // namespace sculpt::core
