#include "sculpt/station/view/surface_lod.h"

#include <algorithm>

namespace sculpt::station {

SurfaceLod::SurfaceLod(int max_level) {
  for (int level = 1; level <= max_level; ++level)
    caches_.push_back(std::make_unique<core::MeshCache>(level));
}

void SurfaceLod::update(const core::Volume& volume, std::span<const int> levels) {
  std::vector<bool> used(caches_.size() + 1, false);
  for (int l : levels) used[static_cast<size_t>(std::clamp(l, 0, max_level()))] = true;
  for (size_t i = 0; i < caches_.size(); ++i) {
    if (used[i + 1] && static_cast<int>(i + 1) <= volume.levels()) caches_[i]->update(volume);
  }
}

const core::BrickMesh& SurfaceLod::brick_mesh(glm::ivec3 b, int level) const {
  return caches_[static_cast<size_t>(level - 1)]->brick_mesh(b);
}

uint64_t SurfaceLod::neighbourhood_stamp(const core::Volume& volume, glm::ivec3 b) {
  const glm::ivec3 g = volume.brick_grid();
  uint64_t sum = 0;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const glm::ivec3 n = b + glm::ivec3(dx, dy, dz);
        if (glm::all(glm::greaterThanEqual(n, glm::ivec3(0))) && glm::all(glm::lessThan(n, g)))
          sum += volume.brick_version(n);
      }
  return sum;
}

}  // namespace sculpt::station
