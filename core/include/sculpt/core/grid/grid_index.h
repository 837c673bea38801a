#pragma once
// The one place a 3D grid position and its x-fastest linear index are
// converted: voxels in a dense grid, bricks in a volume's brick grid, cells
// in a cache. Written out by hand, the order of the products drifted between
// files; here it is fixed.

#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

namespace sculpt::core {

/// (p.z * dims.y + p.y) * dims.x + p.x, for p inside dims.
inline size_t grid_index(glm::ivec3 p, glm::ivec3 dims) {
  return (static_cast<size_t>(p.z) * static_cast<size_t>(dims.y) + static_cast<size_t>(p.y)) *
             static_cast<size_t>(dims.x) +
         static_cast<size_t>(p.x);
}

/// The position of linear index `index` in a grid of `dims` (inverse of grid_index).
inline glm::ivec3 grid_position(int64_t index, glm::ivec3 dims) {
  const int64_t row = dims.x, plane = int64_t{dims.x} * dims.y;
  return {static_cast<int>(index % row), static_cast<int>((index / row) % dims.y),
          static_cast<int>(index / plane)};
}

}  // namespace sculpt::core
